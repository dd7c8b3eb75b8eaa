/*******************************************************************************
*     This file is owned and controlled by Xilinx and must be used solely      *
*     for design, simulation, implementation and creation of design files     *
*     (A wrapper in CORE Generator's shape, written for botsim's tests.)       *
*******************************************************************************/
// You must compile the wrapper file led_map.v when simulating
// the core, led_map. When compiling the wrapper file, be sure to
// reference the XilinxCoreLib Verilog simulation library.

`timescale 1ns/1ps

module led_map(
  clka,
  addra,
  douta
);

input clka;
input [7 : 0] addra;
output [7 : 0] douta;

// synthesis translate_off

  BLK_MEM_GEN_V7_3 #(
    .C_ADDRA_WIDTH(8),
    .C_ADDRB_WIDTH(8),
    .C_ALGORITHM(1),
    .C_BYTE_SIZE(9),
    .C_COMMON_CLK(0),
    .C_DEFAULT_DATA("0"),
    .C_DISABLE_WARN_BHV_COLL(0),
    .C_DISABLE_WARN_BHV_RANGE(0),
    .C_FAMILY("spartan6"),
    .C_HAS_ENA(0),
    .C_HAS_ENB(0),
    .C_HAS_MEM_OUTPUT_REGS_A(0),
    .C_HAS_MEM_OUTPUT_REGS_B(0),
    .C_HAS_MUX_OUTPUT_REGS_A(0),
    .C_HAS_MUX_OUTPUT_REGS_B(0),
    .C_INIT_FILE_NAME("led_map.mif"),
    .C_LOAD_INIT_FILE(1),
    .C_MEM_TYPE(3),
    .C_READ_DEPTH_A(256),
    .C_READ_DEPTH_B(256),
    .C_READ_WIDTH_A(8),
    .C_READ_WIDTH_B(8),
    .C_USE_DEFAULT_DATA(0),
    .C_WRITE_DEPTH_A(256),
    .C_WRITE_MODE_A("WRITE_FIRST"),
    .C_WRITE_WIDTH_A(8),
    .C_XDEVICEFAMILY("spartan6")
  )
  inst (
    .CLKA(clka),
    .ADDRA(addra),
    .DOUTA(douta),
    .RSTA(),
    .ENA(),
    .REGCEA(),
    .WEA(),
    .DINA(),
    .CLKB(),
    .RSTB(),
    .ENB(),
    .REGCEB(),
    .WEB(),
    .ADDRB(),
    .DINB(),
    .DOUTB()
  );

// synthesis translate_on

endmodule
