// bot_model.v: botsim's `bot` for `botsim board --bot model` (not synthesizable).
//
// The same module name, parameter and ports as rtl/bot.v. Behind the registers the course's
// design reads is botsim's model of the bot (core/src/sim/iss.rs: the bot's firmware on the
// cycle-exact instruction-set simulator with Rust models of world_if and the map), called
// once per rising edge of `clk` with the inputs as they are before the edge; it returns what
// world_if holds after the edge. Only the video port is left in Verilog: map.v's second
// port, which reads the same world.
//   pins    = MotCtl_in | reset << 8
//   outputs = LocX | LocY << 8 | BotInfo << 16 | Sensors << 24 | LMDist << 32 |
//             RMDist << 40 | upd_sysregs << 48
`timescale 1ns / 1ps
module bot #(
    parameter WORLD_FILE = ""
) (
    input  wire [7:0] MotCtl_in,
    output wire [7:0] LocX_reg,
`ifdef BOTSIM_LOC_Y_REG
    output wire [7:0] Loc_Y_reg,
`else
    output wire [7:0] LocY_reg,
`endif
    output wire [7:0] Sensors_reg,
    output wire [7:0] BotInfo_reg,
    output wire [7:0] LMDist_reg,
    output wire [7:0] RMDist_reg,
    input  wire [9:0] vid_row,
    input  wire [9:0] vid_col,
    output wire [1:0] vid_pixel_out,
    input  wire       clk,
    input  wire       reset,
    output wire       upd_sysregs
);
    import "DPI-C" function chandle botsim_bot_new(input string path);
    import "DPI-C" function longint botsim_bot_edge(input chandle bot, input int pins);
    chandle model;
    reg [63:0] regs = 64'd0;  // bits 63:49 are zero
    initial model = botsim_bot_new($sformatf("%m"));
    always @(posedge clk) regs <= botsim_bot_edge(model, {23'd0, reset, MotCtl_in});

    wire [7:0] loc_y = regs[15:8];  // by this name for the board wrapper, as in rtl/bot.v
    assign LocX_reg = regs[7:0];
`ifdef BOTSIM_LOC_Y_REG
    assign Loc_Y_reg = loc_y;
`else
    assign LocY_reg = loc_y;
`endif
    assign BotInfo_reg = regs[23:16];
    assign Sensors_reg = regs[31:24];
    assign LMDist_reg = regs[39:32];
    assign RMDist_reg = regs[47:40];
    assign upd_sysregs = regs[48];

    // The video port: the map's second port, as in rtl/bot.v (its first port is unused).
    wire [1:0] unused_loc_info;
    map #(.WORLD_FILE(WORLD_FILE)) MAP (
        .wrld_col_addr(8'h00),
        .wrld_row_addr(8'h00),
        .wrld_loc_info(unused_loc_info),
        .vid_row(vid_row),
        .vid_col(vid_col),
        .vid_pixel_out(vid_pixel_out),
        .clk(clk),
        .reset(reset)
    );
endmodule
