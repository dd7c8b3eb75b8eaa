// nexys3fpga.v: a course Project 2 design for the Nexys3 in the shape of the Winter 2014 ones
// (clean-room, written for botsim from spec board.md): a DCM_SP makes the system clock (CLK0
// through a BUFG, fed back) and the 25 MHz pixel clock (CLKDV); the course's debounce (five
// buttons, the reset active high) and sevensegment (four digits, as the Nexys3 version); the
// team's KCPSM6 with its program ROM beside it in this top, interrupted by upd_sysregs and
// waiting on a semaphore in its scratchpad (proj3demo.psm); the port interface; the bot; and
// a VGA display of the world with the bot as a box, from the course's dtg.
`timescale 1ns / 1ps
module nexys3fpga #(
    parameter SIMULATE = 0
) (
    input  wire       clk100,
    input  wire       btns,
    input  wire       btnl, btnr, btnu, btnd,
    input  wire [7:0] sw,
    output wire [7:0] led,
    output wire [7:0] seg,
    output wire [3:0] an,
    output wire [2:0] vgaRed, vgaGreen,
    output wire [2:1] vgaBlue,
    output wire       Hsync, Vsync
);
    // Clocks: the system on CLK0, the pixel clock on CLKDV.
    wire clkin, clk0, clkdv, clk, pixclk, locked;
    IBUFG CLKIN_BUF (.I(clk100), .O(clkin));
    DCM_SP #(.CLKIN_PERIOD(10.0), .CLKDV_DIVIDE(4.0), .CLK_FEEDBACK("1X")) DCM (
        .CLKIN(clkin), .CLKFB(clk), .CLK0(clk0), .CLKDV(clkdv), .LOCKED(locked), .RST(1'b0),
        .PSEN(1'b0), .PSINCDEC(1'b0), .PSCLK(1'b0), .DSSEN(1'b0)
    );
    BUFG CLK0_BUF (.I(clk0), .O(clk));
    BUFG CLKDV_BUF (.I(clkdv), .O(pixclk));

    // The course's debounce, Nexys3 buttons: bit 0 the reset (active high).
    wire [5:0] db_btns;
    wire [15:0] db_sw;
    debounce #(.RESET_POLARITY_LOW(0), .SIMULATE(SIMULATE)) DB (
        .clk(clk), .pbtn_in({1'b0, btnl, btnu, btnr, btnd, btns}), .switch_in({8'd0, sw}),
        .pbtn_db(db_btns), .swtch_db(db_sw)
    );
    wire sysreset = db_btns[0] | ~locked;

    // The team's PicoBlaze and, beside it, its program.
    wire [11:0] address;
    wire [17:0] instruction;
    wire        bram_enable, rdl;
    wire [ 7:0] port_id, out_port;
    reg  [ 7:0] in_port = 8'd0;
    wire        write_strobe, k_write_strobe, read_strobe, interrupt_ack;
    reg         interrupt = 1'b0;
    kcpsm6 #(.interrupt_vector(12'h3FF), .scratch_pad_memory_size(64), .hwbuild(8'h00)) APPCPU (
        .address(address), .instruction(instruction), .bram_enable(bram_enable),
        .port_id(port_id), .write_strobe(write_strobe), .k_write_strobe(k_write_strobe),
        .out_port(out_port), .read_strobe(read_strobe), .in_port(in_port),
        .interrupt(interrupt), .interrupt_ack(interrupt_ack), .sleep(1'b0),
        .reset(sysreset | rdl), .clk(clk)
    );
    proj3demo APPPGM (.enable(bram_enable), .address(address), .instruction(instruction), .rdl(rdl), .clk(clk));

    // The bot; its video port shows the world.
    reg  [7:0] motctl = 8'd0;
    wire [7:0] locx, locy, botinfo, sensors, lmdist, rmdist;
    wire       upd_sysregs;
    wire [9:0] pixel_row, pixel_column;
    wire [1:0] world_pixel;
    bot ROJOBOT (
        .MotCtl_in(motctl), .LocX_reg(locx), .LocY_reg(locy), .Sensors_reg(sensors),
        .BotInfo_reg(botinfo), .LMDist_reg(lmdist), .RMDist_reg(rmdist),
        .vid_row(pixel_row[8:2]), .vid_col(pixel_column[8:2]), .vid_pixel_out(world_pixel),
        .clk(clk), .reset(sysreset), .upd_sysregs(upd_sysregs)
    );

    // upd_sysregs interrupts the team CPU until it acknowledges.
    always @(posedge clk) begin
        if (interrupt_ack | sysreset) interrupt <= 1'b0;
        else if (upd_sysregs) interrupt <= 1'b1;
    end

    // The port interface (the course's demo port numbers).
    reg [7:0] leds = 8'd0;
    reg [4:0] dig0 = 5'd23, dig1 = 5'd23, dig2 = 5'd23, dig3 = 5'd23;
    reg [3:0] points = 4'd0;
    always @(posedge clk) begin
        case (port_id[3:0])
            4'h0: in_port <= {3'b000, db_btns[5:1]};
            4'h1: in_port <= db_sw[7:0];
            4'hA: in_port <= locx;
            4'hB: in_port <= locy;
            4'hC: in_port <= botinfo;
            4'hD: in_port <= sensors;
            4'hE: in_port <= lmdist;
            4'hF: in_port <= rmdist;
            default: in_port <= 8'h00;
        endcase
    end
    always @(posedge clk) begin
        if (sysreset) begin
            leds <= 8'd0;
            motctl <= 8'd0;
        end else if (write_strobe) begin
            case (port_id)
                8'h02: leds <= out_port;
                8'h03: dig0 <= out_port[4:0];
                8'h04: dig1 <= out_port[4:0];
                8'h05: dig2 <= out_port[4:0];
                8'h06: dig3 <= out_port[4:0];
                8'h07: points <= out_port[3:0];
                8'h09: motctl <= out_port;
                default: ;
            endcase
        end
    end

    // The course's seven-segment driver, the Nexys3's four digits.
    sevensegment #(.RESET_POLARITY_LOW(0), .SIMULATE(SIMULATE)) SSB (
        .clk(clk), .reset(sysreset), .d0(dig0), .d1(dig1), .d2(dig2), .d3(dig3),
        .dp({4'd0, points}), .seg(seg), .an(an), .digits_out()
    );
    assign led = leds;

    // VGA: the world at 4 x 4 pixels a cell, the bot a box of 4 x 4 cells.
    wire hs, vs, video_on;
    dtg DTG (.clock(pixclk), .rst(sysreset), .horiz_sync(hs), .vert_sync(vs), .video_on(video_on),
        .pixel_row(pixel_row), .pixel_column(pixel_column));
    wire at_bot = pixel_column[8:4] == locx[6:2] && pixel_row[8:4] == locy[6:2];
    reg [7:0] rgb = 8'd0;
    always @(posedge pixclk) begin
        if (!video_on) rgb <= 8'd0;
        else if (at_bot) rgb <= 8'b111_000_11;
        else case (world_pixel)
            2'd1: rgb <= 8'b000_000_11;
            2'd2: rgb <= 8'b111_111_00;
            2'd3: rgb <= 8'b111_000_00;
            default: rgb <= 8'b000_111_00;
        endcase
    end
    assign {vgaRed, vgaGreen, vgaBlue} = rgb;
    assign Hsync = hs;
    assign Vsync = vs;
endmodule
