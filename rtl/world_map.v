// world_map.v: the 16K x 2 dual-port world ROM behind map.v (spec botsim.md 9.1).
`timescale 1ns / 1ps
// Both ports read with one clock of latency; no enables. Contents from WORLD_FILE when given.
module world_map #(
    parameter WORLD_FILE = ""
) (
    input  wire        clka,
    input  wire [13:0] addra,
    output reg  [ 1:0] douta = 2'b00,
    input  wire        clkb,
    input  wire [13:0] addrb,
    output reg  [ 1:0] doutb = 2'b00
);
    reg [1:0] cells [0:16383];

    initial begin
        if (WORLD_FILE != "") $readmemh(WORLD_FILE, cells);
    end
`ifdef BOTSIM_WORLD_PLUSARG
    // Board simulation (botsim board): the world comes from the run's +botsim_world=FILE, so
    // one build of a design runs on any map.
    reg [8*4096-1:0] world_path;
    initial begin
        if (WORLD_FILE == "" && $value$plusargs("botsim_world=%s", world_path)) $readmemh(world_path, cells);
    end
`endif

    always @(posedge clka) douta <= cells[addra];
    always @(posedge clkb) doutb <= cells[addrb];
endmodule
