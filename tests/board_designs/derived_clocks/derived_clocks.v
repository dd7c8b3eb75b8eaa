// derived_clocks.v: a board design clocked by clocks made from a generated clock's level
// (test design for botsim board): its LEDs count the rising edges of an MMCME2_ADV's
// inverted 65 MHz output (CLKOUT0B, which rises when CLKOUT0 falls) in their low byte and
// of the same clock through a BUFGCE in their high byte. Both need the harness to evaluate
// the moments at which the generated clock falls.
`timescale 1ns / 1ps
module derived_clocks (
    input  wire        clk,
    input  wire        btnCpuReset,
    output wire [15:0] led
);
    wire clk_in, clk_gen_unbuf, clk_gen, clk_inv, clk_gated, fb_unbuf, fb, locked;
    IBUF ib (.I(clk), .O(clk_in));
    MMCME2_ADV #(
        .BANDWIDTH("OPTIMIZED"), .CLKOUT4_CASCADE("FALSE"), .COMPENSATION("ZHOLD"),
        .STARTUP_WAIT("FALSE"), .DIVCLK_DIVIDE(1), .CLKFBOUT_MULT_F(9.750),
        .CLKFBOUT_PHASE(0.000), .CLKFBOUT_USE_FINE_PS("FALSE"), .CLKOUT0_DIVIDE_F(15.000),
        .CLKOUT0_PHASE(0.000), .CLKOUT0_DUTY_CYCLE(0.500), .CLKOUT0_USE_FINE_PS("FALSE"),
        .CLKIN1_PERIOD(10.0), .REF_JITTER1(0.010)
    ) mmcm_adv_inst (
        .CLKFBOUT(fb_unbuf), .CLKFBOUTB(), .CLKOUT0(clk_gen_unbuf), .CLKOUT0B(clk_inv),
        .CLKOUT1(), .CLKOUT1B(), .CLKOUT2(), .CLKOUT2B(), .CLKOUT3(), .CLKOUT3B(),
        .CLKOUT4(), .CLKOUT5(), .CLKOUT6(),
        .CLKFBIN(fb), .CLKIN1(clk_in), .CLKIN2(1'b0), .CLKINSEL(1'b1),
        .DADDR(7'h0), .DCLK(1'b0), .DEN(1'b0), .DI(16'h0), .DO(), .DRDY(), .DWE(1'b0),
        .PSCLK(1'b0), .PSEN(1'b0), .PSINCDEC(1'b0), .PSDONE(),
        .LOCKED(locked), .CLKINSTOPPED(), .CLKFBSTOPPED(), .PWRDWN(1'b0), .RST(1'b0)
    );
    BUFG fbbuf (.I(fb_unbuf), .O(fb));
    BUFG outbuf (.I(clk_gen_unbuf), .O(clk_gen));
    BUFGCE gate (.I(clk_gen), .CE(locked), .O(clk_gated));

    reg [7:0] inverted = 8'd0, gated = 8'd0;
    always @(posedge clk_inv) inverted <= inverted + 8'd1;
    always @(posedge clk_gated) gated <= gated + 8'd1;
    assign led = {gated, inverted};

    // The design must hold a bot; it runs on the board clock.
    bot ROJOBOT (.MotCtl_in(8'h00), .vid_row(10'd0), .vid_col(10'd0), .clk(clk_in), .reset(~btnCpuReset));
endmodule
