// nexys4fpga_p1.v: Project 1's top (no Rojobot), kept in the repository.
`timescale 1ns / 1ps
module nexys4fpga_p1 (input clk, input btnCpuReset, input [15:0] sw, output [15:0] led);
  reg [15:0] q = 16'd0;
  always @(posedge clk) q <= sw;
  assign led = q;
endmodule
