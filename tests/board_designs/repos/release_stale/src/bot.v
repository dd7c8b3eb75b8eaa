// bot.v: the course's Rojobot as a netlist (a stand-in in its shape, written for botsim's
// tests: the course's is a netlist of Xilinx primitives). botsim replaces it with its own.
`timescale 1ps / 1ps
module bot (input [7:0] MotCtl_in, output [7:0] LocX_reg, output [7:0] LocY_reg,
  output [7:0] Sensors_reg, output [7:0] BotInfo_reg, output [7:0] LMDist_reg, output [7:0] RMDist_reg,
  input [9:0] vid_row, input [9:0] vid_col, output [1:0] vid_pixel_out, input clk, input reset,
  output upd_sysregs);
  FDRE locx_0 (.D(MotCtl_in[0]), .Q(LocX_reg[0]), .CE(1'b1), .R(reset), .C(clk));
  world_map map_rom (.clka(clk), .addra(14'd0), .douta());
endmodule
