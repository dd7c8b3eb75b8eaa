// bot.v: the Rojobot BotSim 2.0 (spec botsim.md 1-2), a drop-in for the course's `bot`.
//
//   bot -+- kcpsm6   BOTSIMCPU  (interrupt_vector 3FF, 64-byte scratch pad, hwbuild 00)
//        +- bot_pgm  BOTSIMPGM  (1K x 18 program ROM, assembled from bot_pgm.psm)
//        +- world_if WRLDIF     (I/O ports, holding and visible registers)
//        +- map      MAP        (128 x 128 x 2-bit world, CPU and video ports)
//
// The firmware samples MotCtl_in once per ~50 ms main-loop iteration, moves the bot in its
// world and publishes LocX/LocY/Sensors/BotInfo (and the deprecated distance counters) with
// a 2-clock upd_sysregs pulse. Reset is synchronous and active high.
//
// Some later copies of the course files spell the Y output `Loc_Y_reg`; define
// BOTSIM_LOC_Y_REG to get that spelling instead of the 2014 release's `LocY_reg`.
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
    wire [11:0] address;
    wire [17:0] instruction;
    wire        bram_enable;
    wire [ 7:0] port_id, out_port, in_port;
    wire        write_strobe, k_write_strobe, read_strobe, interrupt_ack;
    wire [ 7:0] wrld_col_addr, wrld_row_addr;
    wire [ 1:0] wrld_loc_info;
    wire [ 7:0] loc_y;
`ifdef BOTSIM_LOC_Y_REG
    assign Loc_Y_reg = loc_y;
`else
    assign LocY_reg = loc_y;
`endif

    kcpsm6 #(
        .interrupt_vector(12'h3FF),
        .scratch_pad_memory_size(64),
        .hwbuild(8'h00)
    ) BOTSIMCPU (
        .address(address),
        .instruction(instruction),
        .bram_enable(bram_enable),
        .in_port(in_port),
        .out_port(out_port),
        .port_id(port_id),
        .write_strobe(write_strobe),
        .k_write_strobe(k_write_strobe),
        .read_strobe(read_strobe),
        .interrupt(1'b0),
        .interrupt_ack(interrupt_ack),
        .sleep(1'b0),
        .reset(reset),
        .clk(clk)
    );

    // Production-template style: enable, address, instruction, clk (spec kcpsm6.md 3.1).
    bot_pgm BOTSIMPGM (
        .enable(bram_enable),
        .address(address),
        .instruction(instruction),
        .clk(clk)
    );

    world_if WRLDIF (
        .Wr_Strobe(write_strobe),
        .Rd_Strobe(read_strobe),
        .AddrIn(port_id),
        .DataIn(out_port),
        .DataOut(in_port),
        .MotCtl(MotCtl_in),
        .LocX(LocX_reg),
        .LocY(loc_y),
        .BotInfo(BotInfo_reg),
        .Sensors(Sensors_reg),
        .LMDist(LMDist_reg),
        .RMDist(RMDist_reg),
        .MapX(wrld_col_addr),
        .MapY(wrld_row_addr),
        .MapVal(wrld_loc_info),
        .clk(clk),
        .reset(reset),
        .upd_sysregs(upd_sysregs)
    );

    map #(.WORLD_FILE(WORLD_FILE)) MAP (
        .wrld_col_addr(wrld_col_addr),
        .wrld_row_addr(wrld_row_addr),
        .wrld_loc_info(wrld_loc_info),
        .vid_row(vid_row),
        .vid_col(vid_col),
        .vid_pixel_out(vid_pixel_out),
        .clk(clk),
        .reset(reset)
    );

    // interrupt is tied off, so its acknowledge and OUTPUTK's strobe go nowhere (as in 2.0).
    wire unused_ok = &{1'b0, interrupt_ack, k_write_strobe, 1'b0};
endmodule
