// kcpsm6_design_template.v: the release's example of a design around KCPSM6 (a stand-in in
// its shape, written for botsim's tests).
`timescale 1ps / 1ps
module kcpsm6_design_template (input clk);
  wire [11:0] address;
  wire [17:0] instruction;
  wire bram_enable, rdl;
  kcpsm6 #(.interrupt_vector(12'h3FF)) processor (.address(address), .instruction(instruction),
    .bram_enable(bram_enable), .reset(rdl), .clk(clk));
  your_program #(.C_FAMILY("7S")) program_rom (.address(address), .instruction(instruction),
    .enable(bram_enable), .rdl(rdl), .clk(clk));
endmodule
