// clk_wiz_0.v: a clock wrapper in the style the Vivado Clocking Wizard generates (clean-room,
// written for botsim): 100 MHz in, 25 MHz out for 640 x 480 VGA, through IBUF, MMCME2_ADV
// and BUFGs, with the feedback through a BUFG.
`timescale 1ps / 1ps
module clk_wiz_0 (
    input  wire clk_in1,
    output wire clk_out1,
    input  wire reset,
    output wire locked
);
    clk_wiz_0_clk_wiz inst (.clk_in1(clk_in1), .clk_out1(clk_out1), .reset(reset), .locked(locked));
endmodule

module clk_wiz_0_clk_wiz (
    input  wire clk_in1,
    output wire clk_out1,
    input  wire reset,
    output wire locked
);
    wire clk_in1_clk_wiz_0, clk_out1_clk_wiz_0, clkfbout_clk_wiz_0, clkfbout_buf_clk_wiz_0;
    wire clkfboutb_unused, clkout0b_unused, clkout1_unused, clkout1b_unused, clkout2_unused;
    wire clkout2b_unused, clkout3_unused, clkout3b_unused, clkout4_unused, clkout5_unused;
    wire clkout6_unused, drdy_unused, psdone_unused, clkinstopped_unused, clkfbstopped_unused;
    wire [15:0] do_unused;

    IBUF clkin1_ibufg (.O(clk_in1_clk_wiz_0), .I(clk_in1));

    MMCME2_ADV #(
        .BANDWIDTH("OPTIMIZED"), .CLKOUT4_CASCADE("FALSE"), .COMPENSATION("ZHOLD"),
        .STARTUP_WAIT("FALSE"), .DIVCLK_DIVIDE(1), .CLKFBOUT_MULT_F(10.000),
        .CLKFBOUT_PHASE(0.000), .CLKFBOUT_USE_FINE_PS("FALSE"), .CLKOUT0_DIVIDE_F(40.000),
        .CLKOUT0_PHASE(0.000), .CLKOUT0_DUTY_CYCLE(0.500), .CLKOUT0_USE_FINE_PS("FALSE"),
        .CLKIN1_PERIOD(10.0)
    ) mmcm_adv_inst (
        .CLKFBOUT(clkfbout_clk_wiz_0), .CLKFBOUTB(clkfboutb_unused),
        .CLKOUT0(clk_out1_clk_wiz_0), .CLKOUT0B(clkout0b_unused),
        .CLKOUT1(clkout1_unused), .CLKOUT1B(clkout1b_unused), .CLKOUT2(clkout2_unused),
        .CLKOUT2B(clkout2b_unused), .CLKOUT3(clkout3_unused), .CLKOUT3B(clkout3b_unused),
        .CLKOUT4(clkout4_unused), .CLKOUT5(clkout5_unused), .CLKOUT6(clkout6_unused),
        .CLKFBIN(clkfbout_buf_clk_wiz_0), .CLKIN1(clk_in1_clk_wiz_0), .CLKIN2(1'b0),
        .CLKINSEL(1'b1), .DADDR(7'h0), .DCLK(1'b0), .DEN(1'b0), .DI(16'h0), .DO(do_unused),
        .DRDY(drdy_unused), .DWE(1'b0), .PSCLK(1'b0), .PSEN(1'b0), .PSINCDEC(1'b0),
        .PSDONE(psdone_unused), .LOCKED(locked), .CLKINSTOPPED(clkinstopped_unused),
        .CLKFBSTOPPED(clkfbstopped_unused), .PWRDWN(1'b0), .RST(reset)
    );

    BUFG clkf_buf (.O(clkfbout_buf_clk_wiz_0), .I(clkfbout_clk_wiz_0));
    BUFG clkout1_buf (.O(clk_out1), .I(clk_out1_clk_wiz_0));
endmodule
