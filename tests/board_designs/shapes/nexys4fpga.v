// nexys4fpga.v: a course Project 2 board in the shapes teams' designs have and botsim's own
// examples did not (clean-room, written for botsim): a team firmware that polls in a tight
// loop (teampgm.psm), a seven-segment display refreshed from a 2^REFRESH_BITS counter, a
// 32-bit free-running counter, 25 Hz and 10 Hz toggles from clock dividers, and clocks from a
// DCM_SP or an MMCM. Each shape is a parameter, so one design gives every combination:
//
//   CLOCKING   0: all on the 100 MHz oscillator; 1: a DCM_SP, the system on CLK0 and the
//              display on CLKDV (25 MHz), a CLKFX (50 MHz) divider; 2: an MMCM, the system
//              on the oscillator and the display on 25 MHz
//   FREE32     1: a 32-bit counter on every clock; its bit 26 blinks LED 15; 2: its low byte
//              dims LED 15 (lit while below switches 15-8: a PWM); 3: LED 15 shows bit 0 of a
//              32-bit LFSR stepped every clock (a random source a game uses, which never
//              repeats within a run: nothing can be skipped)
//   TOGGLES    1: 25 Hz and 10 Hz toggles nobody reads (a header pin); 2: the 10 Hz one
//              blinks the point of digit 0 and the 25 Hz one LED 14; 3: LED 14 plays a
//              tone, its half period chosen by a `case` on switches 1-0 (a final project's
//              note: Verilator puts the choice of constants into the counter's comparison)
//   REFRESH_BITS  the display counter's width: each digit is lit for 2^(REFRESH_BITS-3)
//              clocks
//   SPRITE     1: a 16 x 16 sprite where the bot is on a 640 x 480 raster, its pixel on LED 13
//              (a team's icon, shown for debugging): the raster on a 25 MHz pixel clock that
//              is a register the design toggles, its row and column compared with the
//              window's edges (registers), the row and column within the window read only
//              inside it
//   WATCHDOG   1: LED 12 lights when a heartbeat (a 9-bit LFSR's tick, every 511 clocks)
//              has not come for 1000 clocks: a count cleared by each tick, or held at 0
//              while bit 19 of a free counter is clear (so it never lights; the count is
//              set to its constant in the middle of a period, which proves nothing alone)
//   FREE_PART  1: LED 11 shows a register that takes a bit of a 15-bit LFSR (stepped every clock,
//              its cycle 32,767 clocks) only while switch 15 is on: off, the LFSR runs
//              apart from everything observed, and the board repeats only with it
//   OWN_CORE   1: a second KCPSM6 (owncore.psm), as a team's own BotSim 3.1 bot has: it waits
//              in four nested delay loops (17 ms), then reads switches 7-0 and shows them on
//              LED 10 and a toggle on LED 9; its read mux registered as the course's
//              world_if31 writes it, a `case` on port_id[3:0] without items 4 and 5 (which
//              keep the last value) and without a default
//
// With the course's debounce (botsim's, board.md 2.1), examples/common's port interface (nexys4_bot_if) and the bot.
`timescale 1ns / 1ps
module nexys4fpga #(
    parameter SIMULATE = 0,
    parameter CLOCKING = 0,
    parameter FREE32 = 0,
    parameter TOGGLES = 0,
    parameter REFRESH_BITS = 18,
    parameter SPRITE = 0,
    parameter WATCHDOG = 0,
    parameter FREE_PART = 0,
    parameter OWN_CORE = 0
) (
    input  wire        clk,
    input  wire        btnCpuReset,
    input  wire        btnC, btnU, btnD, btnL, btnR,
    input  wire [15:0] sw,
    output wire [15:0] led,
    output wire [ 6:0] seg,
    output wire        dp,
    output wire [ 7:0] an,
    output wire [ 7:0] JA
);
    // Clocks: the system's and the display's.
    wire sys_clk, disp_clk, fx_clk, locked;
    generate
        if (CLOCKING == 1) begin : dcm
            wire clk0, clkdv, clkfx;
            DCM_SP #(.CLKDV_DIVIDE(4.0), .CLKFX_DIVIDE(4), .CLKFX_MULTIPLY(2), .CLKIN_PERIOD(10.0),
                     .CLK_FEEDBACK("1X")) DCM (
                .CLKIN(clk), .CLKFB(sys_clk), .RST(1'b0), .CLK0(clk0), .CLKDV(clkdv), .CLKFX(clkfx),
                .LOCKED(locked), .PSEN(1'b0), .PSINCDEC(1'b0), .PSCLK(1'b0), .DSSEN(1'b0)
            );
            BUFG B0 (.I(clk0), .O(sys_clk));
            BUFG B1 (.I(clkdv), .O(disp_clk));
            BUFG B2 (.I(clkfx), .O(fx_clk));
        end else if (CLOCKING == 2) begin : mmcm
            wire fb, c25;
            MMCME2_BASE #(.CLKIN1_PERIOD(10.0), .CLKFBOUT_MULT_F(10.0), .DIVCLK_DIVIDE(1),
                          .CLKOUT0_DIVIDE_F(40.0)) MMCM (
                .CLKIN1(clk), .CLKFBIN(fb), .CLKFBOUT(fb), .CLKOUT0(c25), .LOCKED(locked),
                .RST(1'b0), .PWRDWN(1'b0)
            );
            assign sys_clk = clk;
            BUFG B1 (.I(c25), .O(disp_clk));
            assign fx_clk = clk;
        end else begin : osc
            assign sys_clk = clk;
            assign disp_clk = clk;
            assign fx_clk = clk;
            assign locked = 1'b1;
        end
    endgenerate

    // The course's debounce (board.md 2.1): bit 0 the CPU reset button (active low).
    wire [ 5:0] db_pbtns;
    wire [15:0] db_sw;
    wire [ 4:0] db_btns = db_pbtns[5:1];
    wire        sysreset = ~db_pbtns[0];
    debounce #(.RESET_POLARITY_LOW(1), .SIMULATE(SIMULATE)) DB (
        .clk(sys_clk), .pbtn_in({btnC, btnL, btnU, btnR, btnD, btnCpuReset & locked}), .switch_in(sw),
        .pbtn_db(db_pbtns), .swtch_db(db_sw)
    );

    // The team's PicoBlaze and its polling firmware.
    wire [11:0] address;
    wire [17:0] instruction;
    wire        bram_enable, rdl;
    wire [ 7:0] port_id, out_port, in_port;
    wire        write_strobe, k_write_strobe, read_strobe, interrupt, interrupt_ack;
    kcpsm6 #(.interrupt_vector(12'h3FF), .scratch_pad_memory_size(64), .hwbuild(8'h00)) APPCPU (
        .address(address), .instruction(instruction), .bram_enable(bram_enable),
        .port_id(port_id), .write_strobe(write_strobe), .k_write_strobe(k_write_strobe),
        .out_port(out_port), .read_strobe(read_strobe), .in_port(in_port),
        .interrupt(interrupt), .interrupt_ack(interrupt_ack), .sleep(1'b0),
        .reset(sysreset | rdl), .clk(sys_clk)
    );
    teampgm APPPGM (.enable(bram_enable), .address(address), .instruction(instruction), .rdl(rdl), .clk(sys_clk));

    wire [7:0] motctl, locx, locy, botinfo, sensors, lmdist, rmdist;
    wire       upd_sysregs;
    wire [4:0] dig7, dig6, dig5, dig4, dig3, dig2, dig1, dig0;
    wire [7:0] decpts;
    wire [15:0] leds;
    bot ROJOBOT (
        .MotCtl_in(motctl), .LocX_reg(locx), .LocY_reg(locy), .Sensors_reg(sensors),
        .BotInfo_reg(botinfo), .LMDist_reg(lmdist), .RMDist_reg(rmdist),
        .vid_row(10'd0), .vid_col(10'd0), .vid_pixel_out(),
        .clk(sys_clk), .reset(sysreset), .upd_sysregs(upd_sysregs)
    );
    nexys4_bot_if BOTIF (
        .clk(sys_clk), .reset(sysreset),
        .port_id(port_id), .out_port(out_port), .in_port(in_port),
        .write_strobe(write_strobe), .k_write_strobe(k_write_strobe), .read_strobe(read_strobe),
        .interrupt(interrupt), .interrupt_ack(interrupt_ack),
        .btns(db_btns), .switches(db_sw), .leds(leds),
        .dig7(dig7), .dig6(dig6), .dig5(dig5), .dig4(dig4), .dig3(dig3), .dig2(dig2), .dig1(dig1), .dig0(dig0),
        .decpts(decpts),
        .motctl(motctl), .locx(locx), .locy(locy), .botinfo(botinfo), .sensors(sensors),
        .lmdist(lmdist), .rmdist(rmdist), .upd_sysregs(upd_sysregs)
    );

    // Free-running counters and toggles.
    reg [31:0] free = 32'd0;
    always @(posedge sys_clk) free <= free + 32'd1;
    reg [31:0] lfsr = 32'h1;
    always @(posedge sys_clk) lfsr <= {lfsr[30:0], lfsr[31] ^ lfsr[21] ^ lfsr[1] ^ lfsr[0]};
    wire tog25, tog10;
    divider #(.COUNT(2_000_000)) D25 (.clk(sys_clk), .q(tog25));
    divider #(.COUNT(CLOCKING == 1 ? 2_500_000 : 5_000_000)) D10 (.clk(fx_clk), .q(tog10));

    wire [7:0] points = TOGGLES == 2 ? {decpts[7:1], decpts[0] ^ tog10} : decpts;
    sevenseg #(.BITS(REFRESH_BITS)) SSB (
        .clk(disp_clk),
        .d7(dig7), .d6(dig6), .d5(dig5), .d4(dig4), .d3(dig3), .d2(dig2), .d1(dig1), .d0(dig0),
        .dp(points), .seg(seg), .dp_out(dp), .an(an)
    );

    wire led15 = FREE32 == 1 ? free[26] : FREE32 == 2 ? free[7:0] < sw[15:8] : FREE32 == 3 ? lfsr[0] : leds[15];
    // The tone: a square wave whose half period in clocks the switches choose.
    reg [17:0] half;
    always @(*) begin
        case (sw[1:0])
            2'd0: half = 18'd190840;
            2'd1: half = 18'd113636;
            2'd2: half = 18'd95602;
            default: half = 18'd127551;
        endcase
    end
    reg [17:0] tone_count = 18'd0;
    reg tone = 1'b0;
    always @(posedge sys_clk) begin
        if (tone_count + 18'd1 >= half) begin
            tone_count <= 18'd0;
            tone <= !tone;
        end else begin
            tone_count <= tone_count + 18'd1;
        end
    end
    // The sprite: a pixel clock toggled every other clock, a 800 x 525 raster on it.
    wire led13;
    generate
        if (SPRITE == 1) begin : sprite
            reg pix_en = 1'b0, pix_clk = 1'b0;
            always @(posedge sys_clk) begin
                pix_en <= ~pix_en;
                if (pix_en) pix_clk <= ~pix_clk;
            end
            reg [9:0] h = 10'd0, v = 10'd0;
            always @(posedge pix_clk) begin
                if (h == 10'd799) begin
                    h <= 10'd0;
                    v <= v == 10'd524 ? 10'd0 : v + 10'd1;
                end else begin
                    h <= h + 10'd1;
                end
            end
            reg [9:0] top = 10'd0, bottom = 10'd0, left = 10'd0, right = 10'd0;
            reg [3:0] spr_row = 4'd0, spr_col = 4'd0;
            reg sprite_px = 1'b0;
            always @(posedge pix_clk) begin
                top <= {locy, 2'b00} - 10'd7;
                bottom <= {locy, 2'b00} + 10'd8;
                left <= {locx, 2'b00} - 10'd7;
                right <= {locx, 2'b00} + 10'd8;
                if (v >= top && v <= bottom && h >= left && h <= right) begin
                    spr_row <= v - top;
                    spr_col <= h - left;
                    sprite_px <= spr_row[3] ^ spr_col[0];
                end else begin
                    sprite_px <= 1'b0;
                end
            end
            assign led13 = sprite_px;
        end else begin : no_sprite
            assign led13 = leds[13];
        end
    endgenerate
    // The watchdog.
    wire led12;
    generate
        if (WATCHDOG == 1) begin : watchdog
            reg [17:0] armed = 18'd0;
            reg [8:0] beat = 9'h1ff;
            reg [15:0] since = 16'd0;
            always @(posedge sys_clk) begin
                armed <= armed + 18'd1;
                beat <= {beat[7:0], beat[8] ^ beat[4]};
                if (!armed[17] || beat == 9'h001) since <= 16'd0;
                else since <= since + 16'd1;
            end
            assign led12 = since >= 16'd1000;
        end else begin : no_watchdog
            assign led12 = leds[12];
        end
    endgenerate
    // The free part.
    wire led11;
    generate
        if (FREE_PART == 1) begin : free_part
            reg [14:0] lfsr = 15'h1;
            reg taken = 1'b0;
            always @(posedge sys_clk) begin
                lfsr <= {lfsr[13:0], lfsr[14] ^ lfsr[13]};
                taken <= sw[15] & lfsr[0];
            end
            assign led11 = taken;
        end else begin : no_free_part
            assign led11 = leds[11];
        end
    endgenerate
    // The second core (held in reset but with OWN_CORE = 1).
    wire [11:0] oc_address;
    wire [17:0] oc_instruction;
    wire        oc_bram_enable, oc_rdl, oc_write_strobe, oc_k_write_strobe, oc_read_strobe;
    wire [ 7:0] oc_port_id, oc_out_port;
    reg  [ 7:0] oc_in_port = 8'd0;
    kcpsm6 #(.interrupt_vector(12'h3FF), .scratch_pad_memory_size(64), .hwbuild(8'h00)) OWNCPU (
        .address(oc_address), .instruction(oc_instruction), .bram_enable(oc_bram_enable),
        .port_id(oc_port_id), .write_strobe(oc_write_strobe), .k_write_strobe(oc_k_write_strobe),
        .out_port(oc_out_port), .read_strobe(oc_read_strobe), .in_port(oc_in_port),
        .interrupt(1'b0), .interrupt_ack(), .sleep(1'b0), .reset(sysreset | oc_rdl | OWN_CORE != 1),
        .clk(sys_clk)
    );
    owncore OWNPGM (.enable(oc_bram_enable), .address(oc_address), .instruction(oc_instruction),
        .rdl(oc_rdl), .clk(sys_clk));
    always @(posedge sys_clk) begin
        case (oc_port_id[3:0])
            4'b0000: oc_in_port <= db_sw[7:0];
            4'b0001: oc_in_port <= db_sw[15:8];
            4'b0010: oc_in_port <= {3'd0, db_btns};
            4'b0011: oc_in_port <= 8'h5A;
            4'b0110: oc_in_port <= 8'h00;
            4'b0111: oc_in_port <= 8'hA5;
            4'b1000, 4'b1001, 4'b1010, 4'b1011: oc_in_port <= 8'd0;
            4'b1100, 4'b1101, 4'b1110, 4'b1111: oc_in_port <= 8'hFF;
        endcase
    end
    reg [1:0] oc_shown = 2'd0;
    always @(posedge sys_clk) begin
        if (sysreset) oc_shown <= 2'd0;
        else if (oc_write_strobe) begin
            if (oc_port_id == 8'h01) oc_shown[1] <= |oc_out_port;
            if (oc_port_id == 8'h02) oc_shown[0] <= oc_out_port[0];
        end
    end
    wire [1:0] led10_9 = OWN_CORE == 1 ? oc_shown : leds[10:9];
    assign led = {led15, TOGGLES == 2 ? tog25 : TOGGLES == 3 ? tone : leds[14], led13, led12, led11, led10_9, leds[8:0]};
    assign JA = {6'd0, TOGGLES == 1 ? tog25 : 1'b0, TOGGLES == 1 ? tog10 : 1'b0};
endmodule

// A toggle every COUNT clocks, from a counter that starts over at COUNT - 1.
module divider #(parameter COUNT = 2) (input wire clk, output reg q = 1'b0);
    reg [23:0] n = 24'd0;
    always @(posedge clk)
        if (n == COUNT - 1) begin
            n <= 24'd0;
            q <= ~q;
        end else begin
            n <= n + 24'd1;
        end
endmodule

// Eight multiplexed common-anode digits, each lit for 2^(BITS-3) clocks; codes 00-0F show
// 0-F, 10-1F are dark; outputs active low.
module sevenseg #(parameter BITS = 18) (
    input  wire       clk,
    input  wire [4:0] d7, d6, d5, d4, d3, d2, d1, d0,
    input  wire [7:0] dp,
    output reg  [6:0] seg = 7'h7F,
    output reg        dp_out = 1'b1,
    output reg  [7:0] an = 8'hFF
);
    reg [BITS-1:0] refresh = 0;
    wire [2:0] which = refresh[BITS-1:BITS-3];
    wire [4:0] code = which == 3'd0 ? d0 : which == 3'd1 ? d1 : which == 3'd2 ? d2 : which == 3'd3 ? d3 :
                      which == 3'd4 ? d4 : which == 3'd5 ? d5 : which == 3'd6 ? d6 : d7;
    reg [6:0] lit;
    always @(*)
        case (code)
            5'h00: lit = 7'b0111111; 5'h01: lit = 7'b0000110; 5'h02: lit = 7'b1011011;
            5'h03: lit = 7'b1001111; 5'h04: lit = 7'b1100110; 5'h05: lit = 7'b1101101;
            5'h06: lit = 7'b1111101; 5'h07: lit = 7'b0000111; 5'h08: lit = 7'b1111111;
            5'h09: lit = 7'b1101111; 5'h0A: lit = 7'b1110111; 5'h0B: lit = 7'b1111100;
            5'h0C: lit = 7'b0111001; 5'h0D: lit = 7'b1011110; 5'h0E: lit = 7'b1111001;
            5'h0F: lit = 7'b1110001; default: lit = 7'b0000000;
        endcase
    always @(posedge clk) begin
        refresh <= refresh + 1'b1;
        an <= ~(8'd1 << which);
        seg <= ~lit;
        dp_out <= ~dp[which];
    end
endmodule
