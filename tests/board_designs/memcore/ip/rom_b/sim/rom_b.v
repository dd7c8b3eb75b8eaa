// The simulation wrapper Vivado generates beside a Block Memory Generator core (here in
// outline, written for botsim): it instantiates Xilinx's library model, which botsim does
// not have; botsim models the core from its .xci instead and never reads this module.
`timescale 1ns / 1ps
module rom_b (clka, addra, douta);
  input wire clka;
  input wire [11 : 0] addra;
  output wire [7 : 0] douta;
  blk_mem_gen_v8_3_3 #(.C_FAMILY("artix7"), .C_READ_WIDTH_A(8)) inst (.clka(clka), .addra(addra), .douta(douta));
endmodule
