// nexys4fpga.v: botsim's example of a course Project 2 board design (clean-room, written for
// botsim from spec board.md): the Nexys4 pins around the system in ../common (the team's
// PicoBlaze and firmware, the interface to the Rojobot, the seven-segment display, the bot).
`timescale 1ns / 1ps
module nexys4fpga #(
    parameter SIMULATE = 0
) (
    input  wire        clk,
    input  wire        btnCpuReset,
    input  wire        btnC, btnU, btnD, btnL, btnR,
    input  wire [15:0] sw,
    output wire [15:0] led,
    output wire [ 6:0] seg,
    output wire        dp,
    output wire [ 7:0] an,
    output wire [ 7:0] JA
);
    proj2_system #(.SIMULATE(SIMULATE)) SYS (
        .clk(clk), .btnCpuReset(btnCpuReset), .btnC(btnC), .btnU(btnU), .btnD(btnD), .btnL(btnL),
        .btnR(btnR), .sw(sw), .led(led), .seg(seg), .dp(dp), .an(an), .JA(JA),
        .vid_row(10'd0), .vid_col(10'd0), .vid_pixel_out(), .locx(), .locy(), .botinfo()
    );
endmodule
