// map.v: BotSim 2.0's world: a 128 x 128 x 2-bit dual-port map (spec 9).
//
// Both ports register their address on every clock, and the ROM registers its output, so a
// value appears two clocks after its address: the CPU port (MapX, MapY from world_if) and the
// video port (vid_row, vid_col). Only bits [6:0] of each coordinate are used, so addresses
// wrap modulo 128. `reset` is unused, as in the original.
//
// Cell values: 00 floor, 01 black line, 10 obstruction, 11 reserved.
// The contents come from WORLD_FILE ($readmemh, one value per cell, row-major) when given;
// the simulator loads every world, the built-in one included, into `world.cells` at run time.
`timescale 1ns / 1ps
module map #(
    parameter WORLD_FILE = ""
) (
    input  wire [7:0] wrld_col_addr,
    input  wire [7:0] wrld_row_addr,
    output wire [1:0] wrld_loc_info,
    input  wire [9:0] vid_row,
    input  wire [9:0] vid_col,
    output wire [1:0] vid_pixel_out,
    input  wire       clk,
    input  wire       reset
);
    reg [13:0] wrld_addr = 14'd0;
    reg [13:0] vid_addr = 14'd0;

    always @(posedge clk) begin
        wrld_addr <= {wrld_row_addr[6:0], wrld_col_addr[6:0]};
        vid_addr  <= {vid_row[6:0], vid_col[6:0]};
    end

    world_map #(.WORLD_FILE(WORLD_FILE)) world (
        .clka(clk), .addra(wrld_addr), .douta(wrld_loc_info),
        .clkb(clk), .addrb(vid_addr), .doutb(vid_pixel_out)
    );

    wire unused_ok = &{1'b0, reset, wrld_col_addr[7], wrld_row_addr[7], vid_row[9:7], vid_col[9:7], 1'b0};
endmodule
