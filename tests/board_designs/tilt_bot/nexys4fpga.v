// nexys4fpga.v: a Rojobot steered by tilting the board (clean-room, written for botsim's tests
// from spec board.md 2 and 7): the course's system around the bot (debounce, sevensegment,
// nexys4_bot_if with the course's port numbers, upd_sysregs interrupting the team's
// PicoBlaze), and an SPI master to the board's ADXL362 on ports 20 and 21. The team's program,
// tiltbot.psm, reads the tilt once per bot update and drives the motors from it. The SPI
// master is the one of tests/board_designs/tilt (given beside this file on the command line).
`timescale 1ns / 1ps
module nexys4fpga (
    input  wire        clk,
    input  wire        btnCpuReset,
    input  wire        btnC, btnU, btnD, btnL, btnR,
    input  wire [15:0] sw,
    output wire [15:0] led,
    output wire [ 6:0] seg,
    output wire        dp,
    output wire [ 7:0] an,
    output wire        aclSCK,
    output wire        aclMOSI,
    input  wire        aclMISO,
    output reg         aclSS = 1'b1
);
    wire [ 5:0] db_pbtns;
    wire [15:0] db_sw;
    wire        sysreset = ~db_pbtns[0];
    debounce #(.RESET_POLARITY_LOW(1), .SIMULATE(1)) DB (
        .clk(clk), .pbtn_in({btnC, btnL, btnU, btnR, btnD, btnCpuReset}), .switch_in(sw),
        .pbtn_db(db_pbtns), .swtch_db(db_sw)
    );

    wire [11:0] address;
    wire [17:0] instruction;
    wire        bram_enable, rdl;
    wire [ 7:0] port_id, out_port, bot_in;
    wire        write_strobe, k_write_strobe, read_strobe, interrupt, interrupt_ack;
    reg  [ 7:0] spi_in = 8'd0;
    wire [ 7:0] in_port = port_id[7:4] == 4'h2 ? spi_in : bot_in;
    kcpsm6 #(.interrupt_vector(12'h3FF), .scratch_pad_memory_size(64), .hwbuild(8'h00)) APPCPU (
        .address(address), .instruction(instruction), .bram_enable(bram_enable),
        .port_id(port_id), .write_strobe(write_strobe), .k_write_strobe(k_write_strobe),
        .out_port(out_port), .read_strobe(read_strobe), .in_port(in_port),
        .interrupt(interrupt), .interrupt_ack(interrupt_ack), .sleep(1'b0),
        .reset(sysreset | rdl), .clk(clk)
    );
    tiltbot APPPGM (.enable(bram_enable), .address(address), .instruction(instruction), .rdl(rdl), .clk(clk));

    wire [7:0] motctl, locx, locy, botinfo, sensors, lmdist, rmdist;
    wire       upd_sysregs;
    wire [4:0] dig7, dig6, dig5, dig4, dig3, dig2, dig1, dig0;
    wire [7:0] decpts;
    bot ROJOBOT (
        .MotCtl_in(motctl), .LocX_reg(locx), .LocY_reg(locy), .Sensors_reg(sensors),
        .BotInfo_reg(botinfo), .LMDist_reg(lmdist), .RMDist_reg(rmdist),
        .vid_row(10'd0), .vid_col(10'd0), .vid_pixel_out(),
        .clk(clk), .reset(sysreset), .upd_sysregs(upd_sysregs)
    );
    nexys4_bot_if BOTIF (
        .clk(clk), .reset(sysreset),
        .port_id(port_id), .out_port(out_port), .in_port(bot_in),
        .write_strobe(write_strobe), .k_write_strobe(k_write_strobe), .read_strobe(read_strobe),
        .interrupt(interrupt), .interrupt_ack(interrupt_ack),
        .btns(db_pbtns[5:1]), .switches(db_sw), .leds(led),
        .dig7(dig7), .dig6(dig6), .dig5(dig5), .dig4(dig4), .dig3(dig3), .dig2(dig2), .dig1(dig1), .dig0(dig0),
        .decpts(decpts),
        .motctl(motctl), .locx(locx), .locy(locy), .botinfo(botinfo), .sensors(sensors),
        .lmdist(lmdist), .rmdist(rmdist), .upd_sysregs(upd_sysregs)
    );
    sevensegment #(.RESET_POLARITY_LOW(0), .SIMULATE(1)) SSB (
        .clk(clk), .reset(sysreset),
        .d7(dig7), .d6(dig6), .d5(dig5), .d4(dig4), .d3(dig3), .d2(dig2), .d1(dig1), .d0(dig0),
        .dp(decpts), .seg({dp, seg}), .an(an), .digits_out()
    );

    // The accelerometer's SPI: out 20 a byte, out 21 the select; in 20 the byte read, in 21 busy.
    wire [7:0] spi_rx;
    wire spi_busy;
    spi_master SPI (.clk(clk), .start(write_strobe && port_id == 8'h20), .tx(out_port), .rx(spi_rx),
                    .busy(spi_busy), .sck(aclSCK), .mosi(aclMOSI), .miso(aclMISO));
    always @(posedge clk) begin
        spi_in <= port_id == 8'h21 ? {7'd0, spi_busy} : spi_rx;
        if (write_strobe && port_id == 8'h21) aclSS <= out_port[0];
    end
endmodule
