// world_map.v: the world map, a Block Memory Generator core (16K x 2, dual-port ROM) as the
// core generator writes its simulation wrapper; its contents are in world_map.ngc only.
`timescale 1ns/1ps
module world_map(clka, addra, douta, clkb, addrb, doutb);
input clka;
input [13 : 0] addra;
output [1 : 0] douta;
input clkb;
input [13 : 0] addrb;
output [1 : 0] doutb;
// synthesis translate_off
  BLK_MEM_GEN_V7_2 #(.C_MEM_TYPE(4), .C_READ_WIDTH_A(2), .C_READ_DEPTH_A(16384), .C_LOAD_INIT_FILE(1),
    .C_INIT_FILE_NAME("world_map.mif"), .C_READ_WIDTH_B(2), .C_READ_DEPTH_B(16384))
  inst (.CLKA(clka), .ADDRA(addra), .DOUTA(douta), .CLKB(clkb), .ADDRB(addrb), .DOUTB(doutb));
// synthesis translate_on
endmodule
