// tb_nexys3fpga.v: the team's testbench (simulation only in the project).
`timescale 1ns / 1ps
module tb_nexys3fpga;
  reg clk100 = 0;
  always #5 clk100 = ~clk100;
  Nexys3fpga #(.SIMULATE(1)) uut (.clk100(clk100), .btns(1'b0), .btnl(1'b0), .btnr(1'b0), .btnu(1'b0), .btnd(1'b0), .sw(8'h00));
  initial #1000000 $finish;
endmodule
