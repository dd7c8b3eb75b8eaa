// Icon_Rom.v: the simulation wrapper of a Block Memory Generator ROM, in the shape Vivado
// writes it (clean-room, written for botsim's tests): attributes before a non-ANSI port
// list, and the core's settings as the C_* parameters of Xilinx's library model, which is
// not in the repository (its contents are in Icon_Rom.mif beside it).
`timescale 1 ns / 1 ps

(* X_CORE_INFO = "blk_mem_gen_v8_3_3,Vivado 2016.2" *)
(* CHECK_LICENSE_TYPE = "Icon_Rom,blk_mem_gen_v8_3_3,{}" *)
(* downgradeipidentifiedwarnings = "yes" *)
module Icon_Rom (
  clka,
  addra,
  douta
);

(* X_INTERFACE_INFO = "xilinx.com:interface:bram:1.0 BRAM_PORTA CLK" *)
input wire clka;
(* X_INTERFACE_INFO = "xilinx.com:interface:bram:1.0 BRAM_PORTA ADDR" *)
input wire [10 : 0] addra;
(* X_INTERFACE_INFO = "xilinx.com:interface:bram:1.0 BRAM_PORTA DOUT" *)
output wire [1 : 0] douta;

  blk_mem_gen_v8_3_3 #(
    .C_FAMILY("artix7"),
    .C_XDEVICEFAMILY("artix7"),
    .C_ELABORATION_DIR("./"),
    .C_INTERFACE_TYPE(0),
    .C_AXI_TYPE(1),
    .C_MEM_TYPE(3),
    .C_BYTE_SIZE(9),
    .C_ALGORITHM(1),
    .C_INIT_FILE_NAME("Icon_Rom.mif"),
    .C_INIT_FILE("Icon_Rom.mem"),
    .C_USE_DEFAULT_DATA(0),
    .C_DEFAULT_DATA("0"),
    .C_LOAD_INIT_FILE(1),
    .C_HAS_RSTA(0),
    .C_HAS_ENA(0),
    .C_HAS_REGCEA(0),
    .C_USE_BYTE_WEA(0),
    .C_WEA_WIDTH(1),
    .C_WRITE_MODE_A("WRITE_FIRST"),
    .C_WRITE_WIDTH_A(2),
    .C_READ_WIDTH_A(2),
    .C_WRITE_DEPTH_A(2048),
    .C_READ_DEPTH_A(2048),
    .C_ADDRA_WIDTH(11),
    .C_HAS_MEM_OUTPUT_REGS_A(0),
    .C_HAS_MUX_OUTPUT_REGS_A(0),
    .C_USE_ECC(0),
    .C_COUNT_36K_BRAM("0"),
    .C_COUNT_18K_BRAM("1")
  ) inst (
    .clka(clka),
    .rsta(1'D0),
    .ena(1'D0),
    .regcea(1'D0),
    .wea(1'B0),
    .addra(addra),
    .dina(2'B0),
    .douta(douta),
    .clkb(1'D0),
    .rstb(1'D0),
    .enb(1'D0),
    .regceb(1'D0),
    .web(1'B0),
    .addrb(11'B0),
    .dinb(2'B0),
    .doutb()
  );
endmodule
