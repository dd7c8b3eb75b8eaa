// kcpsm6.v: the release's processor, a netlist of Xilinx primitives (a stand-in in its shape,
// written for botsim's tests: the real one is Xilinx's). botsim replaces it with its own.
`timescale 1ps / 1ps
module kcpsm6 #(parameter [7:0] hwbuild = 8'h00, parameter [11:0] interrupt_vector = 12'h3FF,
                parameter integer scratch_pad_memory_size = 64) (
  output [11:0] address, input [17:0] instruction, output bram_enable, input [7:0] in_port,
  output [7:0] out_port, output [7:0] port_id, output write_strobe, output k_write_strobe,
  output read_strobe, input interrupt, output interrupt_ack, input sleep, input reset, input clk);
  LUT6 #(.INIT(64'h0000000000000002)) reset_lut (.I0(reset), .I1(1'b0), .I2(1'b0), .I3(1'b0), .I4(1'b0), .I5(1'b0), .O(internal_reset));
  FDR run_flop (.D(1'b1), .Q(run), .R(internal_reset), .C(clk));
endmodule
