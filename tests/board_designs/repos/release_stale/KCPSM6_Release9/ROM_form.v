// ROM_form.v: the KCPSM6 release's ROM template (a stand-in written for botsim's tests, in the
// release's shape): the assembler fills {name} and the INIT strings. It declares the same
// JTAG loader module as every ROM made from it.
`timescale 1ps / 1ps
module {name} (input [11:0] address, output [17:0] instruction, input enable, output rdl, input clk);
  RAMB18E1 #(.INIT_00(256'h{INIT_00})) kcpsm6_rom (.ADDRARDADDR({address[9:0], 4'b1111}));
  jtag_loader_6 instantiate_loader (.picoblaze_reset(rdl));
endmodule

module jtag_loader_6 #(parameter integer C_JTAG_LOADER_ENABLE = 1) (output picoblaze_reset);
  BSCANE2 #(.JTAG_CHAIN(2)) BSCAN_BLOCK_inst (.SEL(picoblaze_reset));
endmodule
