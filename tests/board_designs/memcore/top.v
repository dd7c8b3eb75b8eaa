// top.v: a board design with two Xilinx memory cores (test design for botsim board): the
// switches address a Block Memory Generator ROM (rom_b, 8 x 4096, latency 2) shown on
// LED[7:0] and a Distributed Memory Generator ROM (rom_d, 8 x 16, asynchronous) on LED[15:8].
`timescale 1ns / 1ps
module top (
    input  wire        clk,
    input  wire        btnCpuReset,
    input  wire [15:0] sw,
    output wire [15:0] led
);
    rom_b BROM (.clka(clk), .addra(sw[11:0]), .douta(led[7:0]));
    rom_d DROM (.a(sw[3:0]), .spo(led[15:8]));
    bot ROJOBOT (.MotCtl_in(8'h00), .vid_row(10'd0), .vid_col(10'd0), .clk(clk), .reset(~btnCpuReset));
endmodule
