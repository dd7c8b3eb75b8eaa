// clocks.v: a board design whose LEDs count the rising edges of a generated clock (test
// design for botsim board): KIND 0 counts an MMCME2_ADV's 65 MHz CLKOUT0 (100 MHz x 9.75 / 15,
// a non-integer ratio to the board clock), KIND 1 a DCM_SP's 25 MHz CLKFX (x 2 / 8), both
// through BUFGs as a Clocking Wizard wires them. KIND 2 counts clocks made from the MMCM's
// clock's level: its inverted output CLKOUT0B (which rises when CLKOUT0 falls) in the low
// byte, CLKOUT0 through a BUFGCE in the high byte; both need the moments at which the
// generated clock falls evaluated.
`timescale 1ns / 1ps
module clocks #(
    parameter KIND = 0
) (
    input  wire        clk,
    input  wire        btnCpuReset,
    output wire [15:0] led
);
    wire clk_in, clk_gen_unbuf, clk_gen, clk_inv, fb_unbuf, fb, locked;
    IBUF ib (.I(clk), .O(clk_in));
    generate
        if (KIND != 1) begin : mmcm
            MMCME2_ADV #(
                .BANDWIDTH("OPTIMIZED"), .CLKOUT4_CASCADE("FALSE"), .COMPENSATION("ZHOLD"),
                .STARTUP_WAIT("FALSE"), .DIVCLK_DIVIDE(1), .CLKFBOUT_MULT_F(9.750),
                .CLKFBOUT_PHASE(0.000), .CLKFBOUT_USE_FINE_PS("FALSE"), .CLKOUT0_DIVIDE_F(15.000),
                .CLKOUT0_PHASE(0.000), .CLKOUT0_DUTY_CYCLE(0.500), .CLKOUT0_USE_FINE_PS("FALSE"),
                .CLKIN1_PERIOD(10.0), .REF_JITTER1(0.010)
            ) mmcm_adv_inst (
                .CLKFBOUT(fb_unbuf), .CLKFBOUTB(), .CLKOUT0(clk_gen_unbuf), .CLKOUT0B(clk_inv),
                .CLKOUT1(clkout1_unused), .CLKOUT1B(), .CLKOUT2(), .CLKOUT2B(), .CLKOUT3(), .CLKOUT3B(),
                .CLKOUT4(), .CLKOUT5(), .CLKOUT6(),
                .CLKFBIN(fb), .CLKIN1(clk_in), .CLKIN2(1'b0), .CLKINSEL(1'b1),
                .DADDR(7'h0), .DCLK(1'b0), .DEN(1'b0), .DI(16'h0), .DO(), .DRDY(), .DWE(1'b0),
                .PSCLK(1'b0), .PSEN(1'b0), .PSINCDEC(1'b0), .PSDONE(),
                .LOCKED(locked), .CLKINSTOPPED(), .CLKFBSTOPPED(), .PWRDWN(1'b0), .RST(1'b0)
            );
            BUFG fbbuf (.I(fb_unbuf), .O(fb));
        end else begin : dcm
            DCM_SP #(.CLKFX_MULTIPLY(2), .CLKFX_DIVIDE(8), .CLKIN_PERIOD(10.0)) dcm_sp_inst (
                .CLKIN(clk_in), .CLKFB(fb), .CLK0(fb_unbuf), .CLKFX(clk_gen_unbuf), .RST(1'b0),
                .LOCKED(locked), .DSSEN(1'b0), .PSCLK(1'b0), .PSEN(1'b0), .PSINCDEC(1'b0)
            );
            BUFG fbbuf (.I(fb_unbuf), .O(fb));
        end
    endgenerate
    BUFG outbuf (.I(clk_gen_unbuf), .O(clk_gen));

    generate
        if (KIND != 2) begin : count
            reg [15:0] edges = 16'd0;
            always @(posedge clk_gen) edges <= edges + 16'd1;
            assign led = edges;
        end else begin : derived
            wire clk_gated;
            BUFGCE gated_buf (.I(clk_gen), .CE(locked), .O(clk_gated));
            reg [7:0] inverted = 8'd0, gated = 8'd0;
            always @(posedge clk_inv) inverted <= inverted + 8'd1;
            always @(posedge clk_gated) gated <= gated + 8'd1;
            assign led = {gated, inverted};
        end
    endgenerate

    // The design must hold a bot; it runs on the board clock.
    bot ROJOBOT (.MotCtl_in(8'h00), .vid_row(10'd0), .vid_col(10'd0), .clk(clk_in), .reset(~btnCpuReset));
    wire unused_ok = &{1'b0, locked, 1'b0};
endmodule
