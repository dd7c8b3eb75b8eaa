// xilinx.v: behavioural models of the Xilinx primitives that course board designs contain
// (spec board.md 3), for botsim's board simulation only. Clean-room, from the documented
// behaviour: buffers pass their input; the clock managers generate their outputs with
// botsim_clkgen from their parameters (frequency, phase, duty cycle) once "locked".
//
// Lock: LOCKED rises on the 16th rising edge of the input clock after RST (and PWRDWN) fall;
// the outputs run only while locked. An output that no instance in the design connects
// stays low, so it costs nothing: the board build defines BOTSIM_USED_<PRIMITIVE> to the
// mask of outputs any instance connects (bit n = the n-th entry of the model's output list).
`timescale 1ns / 1ps

module BUFG (output wire O, input wire I);
    assign O = I;
endmodule

module BUFH (output wire O, input wire I);
    assign O = I;
endmodule

module IBUF #(parameter IBUF_LOW_PWR = "TRUE", parameter IOSTANDARD = "DEFAULT") (output wire O, input wire I);
    assign O = I;
endmodule

module IBUFG #(parameter IBUF_LOW_PWR = "TRUE", parameter IOSTANDARD = "DEFAULT") (output wire O, input wire I);
    assign O = I;
endmodule

// O follows I while CE, taken while I is low, is high: no glitch.
module BUFGCE (output wire O, input wire CE, input wire I);
    reg en = 1'b0;
    always @(I or CE) if (!I) en = CE;
    assign O = I & en;
endmodule

// The lock counter shared by the clock managers.
module botsim_lock (
    input  wire clk,
    input  wire rst,
    output reg  locked = 1'b0
);
    reg [3:0] count = 4'd0;
    always @(posedge clk or posedge rst) begin
        if (rst) begin
            count  <= 4'd0;
            locked <= 1'b0;
        end else if (count != 4'd15) begin
            count <= count + 4'd1;
        end else begin
            locked <= 1'b1;
        end
    end
endmodule

// MMCM and PLL: f_vco = f_in * M / D; output n = f_vco / O_n. M and O_0 may be fractional
// in steps of 1/8 (MMCM); periods are exact fractions of picoseconds.
// Outputs: bit 0..6 = CLKOUT0..6, bit 7 = CLKFBOUT.
module botsim_mmcm #(
    parameter real CLKIN_PERIOD = 10.0,
    parameter integer DIVCLK_DIVIDE = 1,
    parameter real MULT = 5.0,
    parameter real FB_PHASE = 0.0,
    parameter real D0 = 1.0, parameter real P0 = 0.0, parameter real C0 = 0.5,
    parameter integer D1 = 0, parameter real P1 = 0.0, parameter real C1 = 0.5,
    parameter integer D2 = 0, parameter real P2 = 0.0, parameter real C2 = 0.5,
    parameter integer D3 = 0, parameter real P3 = 0.0, parameter real C3 = 0.5,
    parameter integer D4 = 0, parameter real P4 = 0.0, parameter real C4 = 0.5,
    parameter integer D5 = 0, parameter real P5 = 0.0, parameter real C5 = 0.5,
    parameter integer D6 = 0, parameter real P6 = 0.0, parameter real C6 = 0.5,
    parameter [7:0] USED = 8'hFF
) (
    input  wire       clkin,
    input  wire       rst,
    output wire [6:0] clkout,
    output wire       clkfbout,
    output wire       locked
);
    localparam integer PIN = $rtoi(CLKIN_PERIOD * 1000.0 + 0.5);  // ps
    localparam integer M8 = $rtoi(MULT * 8.0 + 0.5);
    botsim_lock lock (.clk(clkin), .rst(rst), .locked(locked));

    // period_n = PIN * D * O_n / M, in ps: (PIN * D * O8_n) / M8 with O8 = 8 * O_n.
    `define BOTSIM_MMCM_OUT(n, O8, P, C) \
        botsim_clkgen #(.PERIOD_NUM(PIN * DIVCLK_DIVIDE * (O8)), .PERIOD_DEN(M8), \
            .PHASE_MDEG($rtoi((P) * 1000.0)), .DUTY_PERMILLE($rtoi((C) * 1000.0 + 0.5))) \
            out``n (.run(locked & USED[n] & ((O8) != 0)), .clk(clkout[n]));
    `BOTSIM_MMCM_OUT(0, $rtoi(D0 * 8.0 + 0.5), P0, C0)
    `BOTSIM_MMCM_OUT(1, D1 * 8, P1, C1)
    `BOTSIM_MMCM_OUT(2, D2 * 8, P2, C2)
    `BOTSIM_MMCM_OUT(3, D3 * 8, P3, C3)
    `BOTSIM_MMCM_OUT(4, D4 * 8, P4, C4)
    `BOTSIM_MMCM_OUT(5, D5 * 8, P5, C5)
    `BOTSIM_MMCM_OUT(6, D6 * 8, P6, C6)
    `undef BOTSIM_MMCM_OUT
    // The feedback output runs at f_in / D; with D = 1 and no phase it is the input itself.
    generate
        if (DIVCLK_DIVIDE == 1 && FB_PHASE == 0.0) begin : fb_direct
            assign clkfbout = clkin & locked;
        end else begin : fb_gen
            botsim_clkgen #(.PERIOD_NUM(PIN * DIVCLK_DIVIDE), .PERIOD_DEN(1),
                .PHASE_MDEG($rtoi(FB_PHASE * 1000.0)), .DUTY_PERMILLE(500))
                fb (.run(locked & USED[7]), .clk(clkfbout));
        end
    endgenerate
endmodule

// The parameter mapping the four clock managers share (MMCMs add CLKOUT6).
`define BOTSIM_MMCM_PARAMS(MULT_P, D0_P) \
    .CLKIN_PERIOD(CLKIN1_PERIOD), .DIVCLK_DIVIDE(DIVCLK_DIVIDE), .MULT(MULT_P), .FB_PHASE(CLKFBOUT_PHASE), \
    .D0(D0_P), .P0(CLKOUT0_PHASE), .C0(CLKOUT0_DUTY_CYCLE), \
    .D1(CLKOUT1_DIVIDE), .P1(CLKOUT1_PHASE), .C1(CLKOUT1_DUTY_CYCLE), \
    .D2(CLKOUT2_DIVIDE), .P2(CLKOUT2_PHASE), .C2(CLKOUT2_DUTY_CYCLE), \
    .D3(CLKOUT3_DIVIDE), .P3(CLKOUT3_PHASE), .C3(CLKOUT3_DUTY_CYCLE), \
    .D4(CLKOUT4_DIVIDE), .P4(CLKOUT4_PHASE), .C4(CLKOUT4_DUTY_CYCLE), \
    .D5(CLKOUT5_DIVIDE), .P5(CLKOUT5_PHASE), .C5(CLKOUT5_DUTY_CYCLE)

`ifndef BOTSIM_USED_MMCME2_ADV
`define BOTSIM_USED_MMCME2_ADV 8'hFF
`endif
`ifndef BOTSIM_USED_MMCME2_BASE
`define BOTSIM_USED_MMCME2_BASE 8'hFF
`endif
`ifndef BOTSIM_USED_PLLE2_ADV
`define BOTSIM_USED_PLLE2_ADV 8'hFF
`endif
`ifndef BOTSIM_USED_PLLE2_BASE
`define BOTSIM_USED_PLLE2_BASE 8'hFF
`endif
`ifndef BOTSIM_USED_DCM_SP
`define BOTSIM_USED_DCM_SP 8'hFF
`endif

// The parameters and ports of MMCME2_ADV that the Clocking Wizard sets (others may be added
// the same way). CLKOUTnB are the inverted outputs.
module MMCME2_ADV #(
    parameter BANDWIDTH = "OPTIMIZED", parameter CLKOUT4_CASCADE = "FALSE",
    parameter COMPENSATION = "ZHOLD", parameter STARTUP_WAIT = "FALSE",
    parameter integer DIVCLK_DIVIDE = 1, parameter real CLKFBOUT_MULT_F = 5.0,
    parameter real CLKFBOUT_PHASE = 0.0, parameter CLKFBOUT_USE_FINE_PS = "FALSE",
    parameter real CLKOUT0_DIVIDE_F = 1.0, parameter real CLKOUT0_PHASE = 0.0,
    parameter real CLKOUT0_DUTY_CYCLE = 0.5, parameter CLKOUT0_USE_FINE_PS = "FALSE",
    parameter integer CLKOUT1_DIVIDE = 0, parameter real CLKOUT1_PHASE = 0.0,
    parameter real CLKOUT1_DUTY_CYCLE = 0.5, parameter CLKOUT1_USE_FINE_PS = "FALSE",
    parameter integer CLKOUT2_DIVIDE = 0, parameter real CLKOUT2_PHASE = 0.0,
    parameter real CLKOUT2_DUTY_CYCLE = 0.5, parameter CLKOUT2_USE_FINE_PS = "FALSE",
    parameter integer CLKOUT3_DIVIDE = 0, parameter real CLKOUT3_PHASE = 0.0,
    parameter real CLKOUT3_DUTY_CYCLE = 0.5, parameter CLKOUT3_USE_FINE_PS = "FALSE",
    parameter integer CLKOUT4_DIVIDE = 0, parameter real CLKOUT4_PHASE = 0.0,
    parameter real CLKOUT4_DUTY_CYCLE = 0.5, parameter CLKOUT4_USE_FINE_PS = "FALSE",
    parameter integer CLKOUT5_DIVIDE = 0, parameter real CLKOUT5_PHASE = 0.0,
    parameter real CLKOUT5_DUTY_CYCLE = 0.5, parameter CLKOUT5_USE_FINE_PS = "FALSE",
    parameter integer CLKOUT6_DIVIDE = 0, parameter real CLKOUT6_PHASE = 0.0,
    parameter real CLKOUT6_DUTY_CYCLE = 0.5, parameter CLKOUT6_USE_FINE_PS = "FALSE",
    parameter real CLKIN1_PERIOD = 10.0, parameter real CLKIN2_PERIOD = 0.0,
    parameter real REF_JITTER1 = 0.01, parameter real REF_JITTER2 = 0.01,
    parameter SS_EN = "FALSE", parameter SS_MODE = "CENTER_HIGH", parameter integer SS_MOD_PERIOD = 10000,
    parameter [0:0] IS_CLKINSEL_INVERTED = 1'b0, parameter [0:0] IS_PSEN_INVERTED = 1'b0,
    parameter [0:0] IS_PSINCDEC_INVERTED = 1'b0, parameter [0:0] IS_PWRDWN_INVERTED = 1'b0,
    parameter [0:0] IS_RST_INVERTED = 1'b0
) (
    output wire CLKFBOUT, output wire CLKFBOUTB,
    output wire CLKOUT0, output wire CLKOUT0B, output wire CLKOUT1, output wire CLKOUT1B,
    output wire CLKOUT2, output wire CLKOUT2B, output wire CLKOUT3, output wire CLKOUT3B,
    output wire CLKOUT4, output wire CLKOUT5, output wire CLKOUT6,
    output wire LOCKED, output wire CLKINSTOPPED, output wire CLKFBSTOPPED,
    output wire [15:0] DO, output wire DRDY, output wire PSDONE,
    input wire CLKIN1, input wire CLKIN2, input wire CLKINSEL, input wire CLKFBIN,
    input wire RST, input wire PWRDWN,
    input wire [6:0] DADDR, input wire DCLK, input wire DEN, input wire [15:0] DI, input wire DWE,
    input wire PSCLK, input wire PSEN, input wire PSINCDEC
);
    wire [6:0] o;
    botsim_mmcm #(`BOTSIM_MMCM_PARAMS(CLKFBOUT_MULT_F, CLKOUT0_DIVIDE_F),
        .D6(CLKOUT6_DIVIDE), .P6(CLKOUT6_PHASE), .C6(CLKOUT6_DUTY_CYCLE),
        .USED(`BOTSIM_USED_MMCME2_ADV))
        core (.clkin(CLKINSEL ^ IS_CLKINSEL_INVERTED ? CLKIN1 : CLKIN2),
              .rst((RST ^ IS_RST_INVERTED) | (PWRDWN ^ IS_PWRDWN_INVERTED)),
              .clkout(o), .clkfbout(CLKFBOUT), .locked(LOCKED));
    assign {CLKOUT6, CLKOUT5, CLKOUT4, CLKOUT3, CLKOUT2, CLKOUT1, CLKOUT0} = o;
    assign {CLKOUT3B, CLKOUT2B, CLKOUT1B, CLKOUT0B} = ~o[3:0];
    assign CLKFBOUTB = ~CLKFBOUT;
    assign {CLKINSTOPPED, CLKFBSTOPPED, DO, DRDY, PSDONE} = 20'd0;
    wire unused_ok = &{1'b0, CLKFBIN, DADDR, DCLK, DEN, DI, DWE, PSCLK, PSEN, PSINCDEC, IS_PSEN_INVERTED,
                       IS_PSINCDEC_INVERTED, 1'b0};
endmodule

module MMCME2_BASE #(
    parameter BANDWIDTH = "OPTIMIZED", parameter CLKOUT4_CASCADE = "FALSE", parameter STARTUP_WAIT = "FALSE",
    parameter integer DIVCLK_DIVIDE = 1, parameter real CLKFBOUT_MULT_F = 5.0, parameter real CLKFBOUT_PHASE = 0.0,
    parameter real CLKOUT0_DIVIDE_F = 1.0, parameter real CLKOUT0_PHASE = 0.0, parameter real CLKOUT0_DUTY_CYCLE = 0.5,
    parameter integer CLKOUT1_DIVIDE = 0, parameter real CLKOUT1_PHASE = 0.0, parameter real CLKOUT1_DUTY_CYCLE = 0.5,
    parameter integer CLKOUT2_DIVIDE = 0, parameter real CLKOUT2_PHASE = 0.0, parameter real CLKOUT2_DUTY_CYCLE = 0.5,
    parameter integer CLKOUT3_DIVIDE = 0, parameter real CLKOUT3_PHASE = 0.0, parameter real CLKOUT3_DUTY_CYCLE = 0.5,
    parameter integer CLKOUT4_DIVIDE = 0, parameter real CLKOUT4_PHASE = 0.0, parameter real CLKOUT4_DUTY_CYCLE = 0.5,
    parameter integer CLKOUT5_DIVIDE = 0, parameter real CLKOUT5_PHASE = 0.0, parameter real CLKOUT5_DUTY_CYCLE = 0.5,
    parameter integer CLKOUT6_DIVIDE = 0, parameter real CLKOUT6_PHASE = 0.0, parameter real CLKOUT6_DUTY_CYCLE = 0.5,
    parameter real CLKIN1_PERIOD = 10.0, parameter real REF_JITTER1 = 0.01
) (
    output wire CLKFBOUT, output wire CLKFBOUTB,
    output wire CLKOUT0, output wire CLKOUT0B, output wire CLKOUT1, output wire CLKOUT1B,
    output wire CLKOUT2, output wire CLKOUT2B, output wire CLKOUT3, output wire CLKOUT3B,
    output wire CLKOUT4, output wire CLKOUT5, output wire CLKOUT6, output wire LOCKED,
    input wire CLKIN1, input wire CLKFBIN, input wire RST, input wire PWRDWN
);
    wire [6:0] o;
    botsim_mmcm #(`BOTSIM_MMCM_PARAMS(CLKFBOUT_MULT_F, CLKOUT0_DIVIDE_F),
        .D6(CLKOUT6_DIVIDE), .P6(CLKOUT6_PHASE), .C6(CLKOUT6_DUTY_CYCLE),
        .USED(`BOTSIM_USED_MMCME2_BASE))
        core (.clkin(CLKIN1), .rst(RST | PWRDWN), .clkout(o), .clkfbout(CLKFBOUT), .locked(LOCKED));
    assign {CLKOUT6, CLKOUT5, CLKOUT4, CLKOUT3, CLKOUT2, CLKOUT1, CLKOUT0} = o;
    assign {CLKOUT3B, CLKOUT2B, CLKOUT1B, CLKOUT0B} = ~o[3:0];
    assign CLKFBOUTB = ~CLKFBOUT;
    wire unused_ok = &{1'b0, CLKFBIN, 1'b0};
endmodule

// PLLE2: integer multiply and divides; six outputs.
module PLLE2_ADV #(
    parameter BANDWIDTH = "OPTIMIZED", parameter COMPENSATION = "ZHOLD", parameter STARTUP_WAIT = "FALSE",
    parameter integer DIVCLK_DIVIDE = 1, parameter integer CLKFBOUT_MULT = 5, parameter real CLKFBOUT_PHASE = 0.0,
    parameter integer CLKOUT0_DIVIDE = 1, parameter real CLKOUT0_PHASE = 0.0, parameter real CLKOUT0_DUTY_CYCLE = 0.5,
    parameter integer CLKOUT1_DIVIDE = 0, parameter real CLKOUT1_PHASE = 0.0, parameter real CLKOUT1_DUTY_CYCLE = 0.5,
    parameter integer CLKOUT2_DIVIDE = 0, parameter real CLKOUT2_PHASE = 0.0, parameter real CLKOUT2_DUTY_CYCLE = 0.5,
    parameter integer CLKOUT3_DIVIDE = 0, parameter real CLKOUT3_PHASE = 0.0, parameter real CLKOUT3_DUTY_CYCLE = 0.5,
    parameter integer CLKOUT4_DIVIDE = 0, parameter real CLKOUT4_PHASE = 0.0, parameter real CLKOUT4_DUTY_CYCLE = 0.5,
    parameter integer CLKOUT5_DIVIDE = 0, parameter real CLKOUT5_PHASE = 0.0, parameter real CLKOUT5_DUTY_CYCLE = 0.5,
    parameter real CLKIN1_PERIOD = 10.0, parameter real CLKIN2_PERIOD = 0.0,
    parameter real REF_JITTER1 = 0.01, parameter real REF_JITTER2 = 0.01,
    parameter [0:0] IS_CLKINSEL_INVERTED = 1'b0, parameter [0:0] IS_PWRDWN_INVERTED = 1'b0,
    parameter [0:0] IS_RST_INVERTED = 1'b0
) (
    output wire CLKFBOUT, output wire CLKOUT0, output wire CLKOUT1, output wire CLKOUT2,
    output wire CLKOUT3, output wire CLKOUT4, output wire CLKOUT5, output wire LOCKED,
    output wire [15:0] DO, output wire DRDY,
    input wire CLKIN1, input wire CLKIN2, input wire CLKINSEL, input wire CLKFBIN,
    input wire RST, input wire PWRDWN,
    input wire [6:0] DADDR, input wire DCLK, input wire DEN, input wire [15:0] DI, input wire DWE
);
    wire [6:0] o;
    botsim_mmcm #(`BOTSIM_MMCM_PARAMS(CLKFBOUT_MULT, CLKOUT0_DIVIDE),
        .USED(`BOTSIM_USED_PLLE2_ADV))
        core (.clkin(CLKINSEL ^ IS_CLKINSEL_INVERTED ? CLKIN1 : CLKIN2),
              .rst((RST ^ IS_RST_INVERTED) | (PWRDWN ^ IS_PWRDWN_INVERTED)),
              .clkout(o), .clkfbout(CLKFBOUT), .locked(LOCKED));
    assign {CLKOUT5, CLKOUT4, CLKOUT3, CLKOUT2, CLKOUT1, CLKOUT0} = o[5:0];
    assign {DO, DRDY} = 17'd0;
    wire unused_ok = &{1'b0, o[6], CLKFBIN, DADDR, DCLK, DEN, DI, DWE, 1'b0};
endmodule

module PLLE2_BASE #(
    parameter BANDWIDTH = "OPTIMIZED", parameter STARTUP_WAIT = "FALSE",
    parameter integer DIVCLK_DIVIDE = 1, parameter integer CLKFBOUT_MULT = 5, parameter real CLKFBOUT_PHASE = 0.0,
    parameter integer CLKOUT0_DIVIDE = 1, parameter real CLKOUT0_PHASE = 0.0, parameter real CLKOUT0_DUTY_CYCLE = 0.5,
    parameter integer CLKOUT1_DIVIDE = 0, parameter real CLKOUT1_PHASE = 0.0, parameter real CLKOUT1_DUTY_CYCLE = 0.5,
    parameter integer CLKOUT2_DIVIDE = 0, parameter real CLKOUT2_PHASE = 0.0, parameter real CLKOUT2_DUTY_CYCLE = 0.5,
    parameter integer CLKOUT3_DIVIDE = 0, parameter real CLKOUT3_PHASE = 0.0, parameter real CLKOUT3_DUTY_CYCLE = 0.5,
    parameter integer CLKOUT4_DIVIDE = 0, parameter real CLKOUT4_PHASE = 0.0, parameter real CLKOUT4_DUTY_CYCLE = 0.5,
    parameter integer CLKOUT5_DIVIDE = 0, parameter real CLKOUT5_PHASE = 0.0, parameter real CLKOUT5_DUTY_CYCLE = 0.5,
    parameter real CLKIN1_PERIOD = 10.0, parameter real REF_JITTER1 = 0.01
) (
    output wire CLKFBOUT, output wire CLKOUT0, output wire CLKOUT1, output wire CLKOUT2,
    output wire CLKOUT3, output wire CLKOUT4, output wire CLKOUT5, output wire LOCKED,
    input wire CLKIN1, input wire CLKFBIN, input wire RST, input wire PWRDWN
);
    wire [6:0] o;
    botsim_mmcm #(`BOTSIM_MMCM_PARAMS(CLKFBOUT_MULT, CLKOUT0_DIVIDE),
        .USED(`BOTSIM_USED_PLLE2_BASE))
        core (.clkin(CLKIN1), .rst(RST | PWRDWN), .clkout(o), .clkfbout(CLKFBOUT), .locked(LOCKED));
    assign {CLKOUT5, CLKOUT4, CLKOUT3, CLKOUT2, CLKOUT1, CLKOUT0} = o[5:0];
    wire unused_ok = &{1'b0, o[6], CLKFBIN, 1'b0};
endmodule

// Spartan-6 DCM_SP. Outputs: bit 0 CLK0, 1 CLK90, 2 CLK180, 3 CLK270, 4 CLK2X, 5 CLK2X180,
// 6 CLKDV, 7 CLKFX (and CLKFX180).
module DCM_SP #(
    parameter real CLKDV_DIVIDE = 2.0, parameter integer CLKFX_DIVIDE = 1, parameter integer CLKFX_MULTIPLY = 4,
    parameter CLKIN_DIVIDE_BY_2 = "FALSE", parameter real CLKIN_PERIOD = 10.0,
    parameter CLKOUT_PHASE_SHIFT = "NONE", parameter CLK_FEEDBACK = "1X",
    parameter DESKEW_ADJUST = "SYSTEM_SYNCHRONOUS", parameter DFS_FREQUENCY_MODE = "LOW",
    parameter DLL_FREQUENCY_MODE = "LOW", parameter DSS_MODE = "NONE",
    parameter DUTY_CYCLE_CORRECTION = "TRUE", parameter [15:0] FACTORY_JF = 16'hC080,
    parameter integer PHASE_SHIFT = 0, parameter STARTUP_WAIT = "FALSE"
) (
    output wire CLK0, output wire CLK180, output wire CLK270, output wire CLK2X, output wire CLK2X180,
    output wire CLK90, output wire CLKDV, output wire CLKFX, output wire CLKFX180, output wire LOCKED,
    output wire PSDONE, output wire [7:0] STATUS,
    input wire CLKFB, input wire CLKIN, input wire DSSEN, input wire PSCLK, input wire PSEN,
    input wire PSINCDEC, input wire RST
);
    localparam [7:0] USED = `BOTSIM_USED_DCM_SP;
    localparam integer PIN = $rtoi(CLKIN_PERIOD * 1000.0 + 0.5) * (CLKIN_DIVIDE_BY_2 == "TRUE" ? 2 : 1);
    wire locked;
    botsim_lock lock (.clk(CLKIN), .rst(RST), .locked(locked));
    assign LOCKED = locked;
    // CLK0 and CLK180 are the input itself (with CLKIN_DIVIDE_BY_2, a generated clock).
    generate
        if (CLKIN_DIVIDE_BY_2 == "TRUE") begin : half
            botsim_clkgen #(.PERIOD_NUM(PIN)) c0 (.run(locked & |USED[2:0]), .clk(CLK0));
        end else begin : direct
            assign CLK0 = CLKIN & locked;
        end
    endgenerate
    assign CLK180 = ~CLK0 & locked;
    botsim_clkgen #(.PERIOD_NUM(PIN), .PHASE_MDEG(90000)) c90 (.run(locked & |{USED[1], USED[3]}), .clk(CLK90));
    assign CLK270 = ~CLK90 & locked;
    botsim_clkgen #(.PERIOD_NUM(PIN), .PERIOD_DEN(2)) c2x (.run(locked & |USED[5:4]), .clk(CLK2X));
    assign CLK2X180 = ~CLK2X & locked;
    botsim_clkgen #(.PERIOD_NUM(PIN * $rtoi(CLKDV_DIVIDE * 2.0 + 0.5)), .PERIOD_DEN(2))
        cdv (.run(locked & USED[6]), .clk(CLKDV));
    botsim_clkgen #(.PERIOD_NUM(PIN * CLKFX_DIVIDE), .PERIOD_DEN(CLKFX_MULTIPLY))
        cfx (.run(locked & USED[7]), .clk(CLKFX));
    assign CLKFX180 = ~CLKFX & locked;
    assign {PSDONE, STATUS} = 9'd0;
    wire unused_ok = &{1'b0, CLKFB, DSSEN, PSCLK, PSEN, PSINCDEC, 1'b0};
endmodule

// ---- Logic primitives (7-series and Spartan-6 libraries), as designs instantiate them by
// hand: the KCPSM6 package's UART macros, teams' own optimised blocks. Each as its library
// guide describes it: a LUT's output is the bit of INIT its inputs address (I0 the least
// significant); a flip-flop takes D at C's rising edge (CE enabling it; R/S synchronous,
// CLR/PRE asynchronous, each over CE) and starts at INIT; an SRL shifts D in at bit 0 while
// CE and outputs the bit its address selects (Q31: the last); the wide multiplexers pick I1
// when S is high; CARRY4 is the slice's carry chain. The IS_*_INVERTED attributes of the
// 7-series flip-flops invert that pin.

module LUT1 #(parameter [1:0] INIT = 2'h0) (output wire O, input wire I0);
    assign O = INIT[I0];
endmodule
module LUT2 #(parameter [3:0] INIT = 4'h0) (output wire O, input wire I0, I1);
    assign O = INIT[{I1, I0}];
endmodule
module LUT3 #(parameter [7:0] INIT = 8'h0) (output wire O, input wire I0, I1, I2);
    assign O = INIT[{I2, I1, I0}];
endmodule
module LUT4 #(parameter [15:0] INIT = 16'h0) (output wire O, input wire I0, I1, I2, I3);
    assign O = INIT[{I3, I2, I1, I0}];
endmodule
module LUT5 #(parameter [31:0] INIT = 32'h0) (output wire O, input wire I0, I1, I2, I3, I4);
    assign O = INIT[{I4, I3, I2, I1, I0}];
endmodule
module LUT6 #(parameter [63:0] INIT = 64'h0) (output wire O, input wire I0, I1, I2, I3, I4, I5);
    assign O = INIT[{I5, I4, I3, I2, I1, I0}];
endmodule
// O6 from all 64 bits; O5 from the lower 32 by I0-I4 (I5 ignored).
module LUT6_2 #(parameter [63:0] INIT = 64'h0) (output wire O6, O5, input wire I0, I1, I2, I3, I4, I5);
    assign O6 = INIT[{I5, I4, I3, I2, I1, I0}];
    assign O5 = INIT[{1'b0, I4, I3, I2, I1, I0}];
endmodule

module MUXF7 (output wire O, input wire I0, I1, S);
    assign O = S ? I1 : I0;
endmodule
module MUXF8 (output wire O, input wire I0, I1, S);
    assign O = S ? I1 : I0;
endmodule
// Spartan-6 / Virtex-5 carry elements.
module MUXCY (output wire O, input wire CI, DI, S);
    assign O = S ? CI : DI;
endmodule
module XORCY (output wire O, input wire CI, LI);
    assign O = CI ^ LI;
endmodule
// The 7-series carry chain: bit n propagates the carry where S[n] is high, else takes DI[n];
// O[n] = S[n] xor the carry into it; the carry in is CI or CYINIT.
module CARRY4 (output wire [3:0] CO, O, input wire CI, CYINIT, input wire [3:0] DI, S);
    wire c0 = CI | CYINIT;
    assign CO[0] = S[0] ? c0 : DI[0];
    assign CO[1] = S[1] ? CO[0] : DI[1];
    assign CO[2] = S[2] ? CO[1] : DI[2];
    assign CO[3] = S[3] ? CO[2] : DI[3];
    assign O = S ^ {CO[2:0], c0};
endmodule

// Flip-flops with a synchronous reset or set (R/S over CE).
module FD #(parameter [0:0] INIT = 1'b0) (output reg Q = INIT, input wire C, D);
    always @(posedge C) Q <= D;
endmodule
module FDE #(parameter [0:0] INIT = 1'b0) (output reg Q = INIT, input wire C, CE, D);
    always @(posedge C) if (CE) Q <= D;
endmodule
module FDR #(parameter [0:0] INIT = 1'b0) (output reg Q = INIT, input wire C, D, R);
    always @(posedge C) Q <= R ? 1'b0 : D;
endmodule
module FDS #(parameter [0:0] INIT = 1'b1) (output reg Q = INIT, input wire C, D, S);
    always @(posedge C) Q <= S ? 1'b1 : D;
endmodule
module FDRE #(
    parameter [0:0] INIT = 1'b0,
    parameter [0:0] IS_C_INVERTED = 1'b0,
    parameter [0:0] IS_D_INVERTED = 1'b0,
    parameter [0:0] IS_R_INVERTED = 1'b0
) (output reg Q = INIT, input wire C, CE, D, R);
    wire c = C ^ IS_C_INVERTED;
    always @(posedge c) begin
        if (R ^ IS_R_INVERTED) Q <= 1'b0;
        else if (CE) Q <= D ^ IS_D_INVERTED;
    end
endmodule
module FDSE #(
    parameter [0:0] INIT = 1'b1,
    parameter [0:0] IS_C_INVERTED = 1'b0,
    parameter [0:0] IS_D_INVERTED = 1'b0,
    parameter [0:0] IS_S_INVERTED = 1'b0
) (output reg Q = INIT, input wire C, CE, D, S);
    wire c = C ^ IS_C_INVERTED;
    always @(posedge c) begin
        if (S ^ IS_S_INVERTED) Q <= 1'b1;
        else if (CE) Q <= D ^ IS_D_INVERTED;
    end
endmodule
// Flip-flops with an asynchronous clear or preset.
module FDC #(parameter [0:0] INIT = 1'b0) (output reg Q = INIT, input wire C, CLR, D);
    always @(posedge C or posedge CLR) Q <= CLR ? 1'b0 : D;
endmodule
module FDP #(parameter [0:0] INIT = 1'b1) (output reg Q = INIT, input wire C, D, PRE);
    always @(posedge C or posedge PRE) Q <= PRE ? 1'b1 : D;
endmodule
module FDCE #(
    parameter [0:0] INIT = 1'b0,
    parameter [0:0] IS_C_INVERTED = 1'b0,
    parameter [0:0] IS_CLR_INVERTED = 1'b0,
    parameter [0:0] IS_D_INVERTED = 1'b0
) (output reg Q = INIT, input wire C, CE, CLR, D);
    wire c = C ^ IS_C_INVERTED, clr = CLR ^ IS_CLR_INVERTED;
    always @(posedge c or posedge clr) begin
        if (clr) Q <= 1'b0;
        else if (CE) Q <= D ^ IS_D_INVERTED;
    end
endmodule
module FDPE #(
    parameter [0:0] INIT = 1'b1,
    parameter [0:0] IS_C_INVERTED = 1'b0,
    parameter [0:0] IS_D_INVERTED = 1'b0,
    parameter [0:0] IS_PRE_INVERTED = 1'b0
) (output reg Q = INIT, input wire C, CE, D, PRE);
    wire c = C ^ IS_C_INVERTED, pre = PRE ^ IS_PRE_INVERTED;
    always @(posedge c or posedge pre) begin
        if (pre) Q <= 1'b1;
        else if (CE) Q <= D ^ IS_D_INVERTED;
    end
endmodule

// Shift registers in a LUT.
module SRL16E #(parameter [15:0] INIT = 16'h0, parameter [0:0] IS_CLK_INVERTED = 1'b0) (
    output wire Q, input wire A0, A1, A2, A3, CE, CLK, D
);
    reg [15:0] data = INIT;
    wire c = CLK ^ IS_CLK_INVERTED;
    always @(posedge c) if (CE) data <= {data[14:0], D};
    assign Q = data[{A3, A2, A1, A0}];
endmodule
module SRLC32E #(parameter [31:0] INIT = 32'h0, parameter [0:0] IS_CLK_INVERTED = 1'b0) (
    output wire Q, Q31, input wire [4:0] A, input wire CE, CLK, D
);
    reg [31:0] data = INIT;
    wire c = CLK ^ IS_CLK_INVERTED;
    always @(posedge c) if (CE) data <= {data[30:0], D};
    assign Q = data[A];
    assign Q31 = data[31];
endmodule
