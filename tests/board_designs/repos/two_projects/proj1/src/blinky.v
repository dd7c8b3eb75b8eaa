// blinky.v: Project 1, LEDs that count (no Rojobot).
`timescale 1ns / 1ps
module blinky (input clk, input btnCpuReset, output [15:0] led);
  reg [41:0] count = 42'd0;
  always @(posedge clk) count <= btnCpuReset ? count + 42'd1 : 42'd0;
  assign led = count[41:26];
endmodule
