// tb_nexys4fpga.v: the team's testbench (never part of the design).
`timescale 1ns / 1ps
module tb_nexys4fpga;
  reg clk = 0, btnCpuReset = 0;
  always #5 clk = ~clk;
  nexys4fpga #(.SIMULATE(1)) dut (.clk(clk), .btnCpuReset(btnCpuReset), .btnC(1'b0), .btnU(1'b0),
    .btnD(1'b0), .btnL(1'b0), .btnR(1'b0), .sw(16'h0000));
  initial begin #100 btnCpuReset = 1; #2000000 $finish; end
endmodule
