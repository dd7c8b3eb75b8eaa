// nexys3fpga.v: a Project 2 top for the Nexys3 (clean-room, written for botsim's tests): the
// system with its Nexys4 ports folded onto the Nexys3's (btns resets, 8 switches, 8 LEDs
// mirrored through a ROM on the 25 MHz clock, four digits with the point in seg[7]).
`timescale 1ns / 1ps
module Nexys3fpga #(parameter SIMULATE = 0) (
    input  wire       clk100,
    input  wire       btns,
    input  wire       btnl, btnr, btnu, btnd,
    input  wire [7:0] sw,
    output wire [7:0] led,
    output wire [7:0] seg,
    output wire [3:0] an
);
    wire [15:0] sys_led;
    wire [ 6:0] seg7;
    wire [ 7:0] an8;
    wire        dp, clk25, locked;

    proj2_system #(.SIMULATE(SIMULATE)) SYS (
        .clk(clk100), .btnCpuReset(~btns), .btnC(1'b0), .btnU(btnu), .btnD(btnd), .btnL(btnl),
        .btnR(btnr), .sw({8'h00, sw}), .led(sys_led), .seg(seg7), .dp(dp), .an(an8), .JA(),
        .vid_row(10'd0), .vid_col(10'd0), .vid_pixel_out(), .locx(), .locy(), .botinfo()
    );

    clk25 CLKGEN (.CLK_IN1(clk100), .CLK_OUT1(clk25), .RESET(btns), .LOCKED(locked));

    // The LEDs sit the other way round on this board: mirrored by a ROM.
    led_map LEDS (.clka(clk25), .addra(sys_led[7:0]), .douta(led));

    assign seg = {dp, seg7};
    assign an = an8[3:0];
endmodule
