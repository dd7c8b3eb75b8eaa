// proj2_system.v: the system of botsim's example course designs (clean-room, written for
// botsim from spec board.md): a debounced reset and buttons, a seven-segment driver, the
// team's own KCPSM6 running proj2demo.psm, the interface between it and the Rojobot's
// registers (upd_sysregs interrupts the team CPU), and the `bot` itself, whose video port and
// registers it passes out for a display.
`timescale 1ns / 1ps
module proj2_system #(
    parameter SIMULATE = 0
) (
    input  wire        clk,
    input  wire        btnCpuReset,
    input  wire        btnC, btnU, btnD, btnL, btnR,
    input  wire [15:0] sw,
    output wire [15:0] led,
    output wire [ 6:0] seg,
    output wire        dp,
    output wire [ 7:0] an,
    output wire [ 7:0] JA,
    input  wire [ 9:0] vid_row,
    input  wire [ 9:0] vid_col,
    output wire [ 1:0] vid_pixel_out,
    output wire [ 7:0] locx,
    output wire [ 7:0] locy,
    output wire [ 7:0] botinfo
);
    // The course's debounce (spec board.md 2.1): bit 0 the CPU reset button (active low).
    wire [ 5:0] db_pbtns;
    wire [15:0] db_sw;
    wire [ 4:0] db_btns = db_pbtns[5:1];
    wire        sysreset = ~db_pbtns[0];

    debounce #(.RESET_POLARITY_LOW(1), .SIMULATE(SIMULATE)) DB (
        .clk(clk), .pbtn_in({btnC, btnL, btnU, btnR, btnD, btnCpuReset}), .switch_in(sw),
        .pbtn_db(db_pbtns), .swtch_db(db_sw)
    );

    // The team's PicoBlaze and its program.
    wire [11:0] address;
    wire [17:0] instruction;
    wire        bram_enable, rdl;
    wire [ 7:0] port_id, out_port, in_port;
    wire        write_strobe, k_write_strobe, read_strobe;
    wire        interrupt, interrupt_ack;

    kcpsm6 #(.interrupt_vector(12'h3FF), .scratch_pad_memory_size(64), .hwbuild(8'h00)) APPCPU (
        .address(address), .instruction(instruction), .bram_enable(bram_enable),
        .port_id(port_id), .write_strobe(write_strobe), .k_write_strobe(k_write_strobe),
        .out_port(out_port), .read_strobe(read_strobe), .in_port(in_port),
        .interrupt(interrupt), .interrupt_ack(interrupt_ack), .sleep(1'b0),
        .reset(sysreset | rdl), .clk(clk)
    );

    proj2demo #(.C_FAMILY("7S"), .C_RAM_SIZE_KWORDS(1), .C_JTAG_LOADER_ENABLE(0)) APPPGM (
        .enable(bram_enable), .address(address), .instruction(instruction), .rdl(rdl), .clk(clk)
    );

    // The Rojobot and the interface to it.
    wire [7:0] motctl, sensors, lmdist, rmdist;
    wire       upd_sysregs;
    wire [4:0] dig7, dig6, dig5, dig4, dig3, dig2, dig1, dig0;
    wire [7:0] decpts;
    wire [15:0] leds;

    bot ROJOBOT (
        .MotCtl_in(motctl), .LocX_reg(locx), .LocY_reg(locy), .Sensors_reg(sensors),
        .BotInfo_reg(botinfo), .LMDist_reg(lmdist), .RMDist_reg(rmdist),
        .vid_row(vid_row), .vid_col(vid_col), .vid_pixel_out(vid_pixel_out),
        .clk(clk), .reset(sysreset), .upd_sysregs(upd_sysregs)
    );

    nexys4_bot_if BOTIF (
        .clk(clk), .reset(sysreset),
        .port_id(port_id), .out_port(out_port), .in_port(in_port),
        .write_strobe(write_strobe), .k_write_strobe(k_write_strobe), .read_strobe(read_strobe),
        .interrupt(interrupt), .interrupt_ack(interrupt_ack),
        .btns(db_btns), .switches(db_sw), .leds(leds),
        .dig7(dig7), .dig6(dig6), .dig5(dig5), .dig4(dig4), .dig3(dig3), .dig2(dig2), .dig1(dig1), .dig0(dig0),
        .decpts(decpts),
        .motctl(motctl), .locx(locx), .locy(locy), .botinfo(botinfo), .sensors(sensors),
        .lmdist(lmdist), .rmdist(rmdist), .upd_sysregs(upd_sysregs)
    );

    // The course's seven-segment driver (board.md 2.1), reset by the active-high sysreset.
    sevensegment #(.RESET_POLARITY_LOW(0), .SIMULATE(SIMULATE)) SSB (
        .clk(clk), .reset(sysreset),
        .d7(dig7), .d6(dig6), .d5(dig5), .d4(dig4), .d3(dig3), .d2(dig2), .d1(dig1), .d0(dig0),
        .dp(decpts), .seg({dp, seg}), .an(an), .digits_out()
    );

    assign led = leds;
    assign JA = {clk, sysreset, upd_sysregs, interrupt, interrupt_ack, 3'b000};
endmodule
