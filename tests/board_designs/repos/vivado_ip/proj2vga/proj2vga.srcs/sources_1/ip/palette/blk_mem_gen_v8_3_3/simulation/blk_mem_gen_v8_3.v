// blk_mem_gen_v8_3.v: Xilinx's behavioural library model of the Block Memory Generator, as
// Vivado leaves it beside a core (a stand-in in its shape, written for botsim's tests: the
// real one is thousands of lines of simulator-specific code). Timing checks and delays that
// Verilator refuses without --timing: botsim must never compile it.
`timescale 1ps / 1ps
module blk_mem_gen_v8_3_3 #(parameter C_FAMILY = "virtex7", parameter C_READ_WIDTH_A = 1,
                            parameter C_ADDRA_WIDTH = 1, parameter C_INIT_FILE_NAME = "")
  (input clka, input ena, input regcea, input wea, input [C_ADDRA_WIDTH-1:0] addra,
   input [C_READ_WIDTH_A-1:0] dina, output reg [C_READ_WIDTH_A-1:0] douta);
  reg [C_READ_WIDTH_A-1:0] memory [0:(1<<C_ADDRA_WIDTH)-1];
  initial begin
    #100;
    $readmemb(C_INIT_FILE_NAME, memory);
  end
  always @(posedge clka) begin
    #1 douta <= memory[addra];
  end
  specify
    $setuphold(posedge clka, addra, 0:0:0, 0:0:0);
  endspecify
endmodule
