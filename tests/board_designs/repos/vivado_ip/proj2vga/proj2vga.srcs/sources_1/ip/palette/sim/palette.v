// palette.v: the simulation wrapper Vivado generates for the `palette` core (a stand-in in
// its shape, written for botsim's tests): it instantiates Xilinx's library model.
`timescale 1ns / 1ps
module palette (clka, addra, douta);
  input wire clka;
  input wire [4 : 0] addra;
  output wire [11 : 0] douta;
  blk_mem_gen_v8_3_3 #(
    .C_FAMILY("artix7"), .C_MEM_TYPE(3), .C_INIT_FILE_NAME("palette.mif"), .C_LOAD_INIT_FILE(1),
    .C_HAS_ENA(0), .C_READ_WIDTH_A(12), .C_WRITE_WIDTH_A(12), .C_READ_DEPTH_A(32), .C_WRITE_DEPTH_A(32),
    .C_ADDRA_WIDTH(5), .C_HAS_MEM_OUTPUT_REGS_A(0), .C_HAS_MUX_OUTPUT_REGS_A(0)
  ) inst (.clka(clka), .ena(1'b0), .regcea(1'b0), .wea(1'b0), .addra(addra), .dina(12'b0), .douta(douta));
endmodule
