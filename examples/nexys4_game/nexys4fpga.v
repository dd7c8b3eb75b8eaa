// nexys4fpga.v: a final-project-shaped design without a bot (clean-room, written for botsim
// from spec board.md 1, 2, 2.1 and 7): a VGA game. The team's PicoBlaze runs game.psm: a
// 16 x 16 box bounces around the 640 x 480 screen on its own, one step of 4 pixels a frame
// in x and in y; the buttons set its direction (left, right, up, down); each bounce counts
// on the seven-segment display (decimal), and the LEDs show its place (x on 7-0, y on
// 15-8); the keyboard's arrow keys held are the same as the buttons (arrows.v). The CPU is
// interrupted at each frame's vertical sync and waits on a scratchpad semaphore, as the
// course's Project 2 firmware does. The course's debounce and
// sevensegment are not committed (botsim brings them); a 25 MHz pixel clock from an MMCM.
`timescale 1ns / 1ps
module nexys4fpga #(
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
    output reg  [ 3:0] vgaRed = 4'd0,
    output reg  [ 3:0] vgaGreen = 4'd0,
    output reg  [ 3:0] vgaBlue = 4'd0,
    output reg         Hsync = 1'b1,
    output reg         Vsync = 1'b1,
    input  wire        PS2Clk,
    input  wire        PS2Data
);
    // The course's debounce (board.md 2.1): bit 0 the CPU reset button (active low).
    wire [ 5:0] db_pbtns;
    wire [15:0] db_sw;
    wire        sysreset = ~db_pbtns[0];
    debounce #(.RESET_POLARITY_LOW(1), .SIMULATE(SIMULATE)) DB (
        .clk(clk), .pbtn_in({btnC, btnL, btnU, btnR, btnD, btnCpuReset}), .switch_in(sw),
        .pbtn_db(db_pbtns), .swtch_db(db_sw)
    );

    // The team's PicoBlaze and its program (game.psm).
    wire [11:0] address;
    wire [17:0] instruction;
    wire        bram_enable, rdl;
    wire [ 7:0] port_id, out_port;
    reg  [ 7:0] in_port = 8'd0;
    wire        write_strobe, k_write_strobe, read_strobe, interrupt_ack;
    reg         interrupt = 1'b0;
    kcpsm6 #(.interrupt_vector(12'h3FF), .scratch_pad_memory_size(64), .hwbuild(8'h00)) GAMECPU (
        .address(address), .instruction(instruction), .bram_enable(bram_enable),
        .port_id(port_id), .write_strobe(write_strobe), .k_write_strobe(k_write_strobe),
        .out_port(out_port), .read_strobe(read_strobe), .in_port(in_port),
        .interrupt(interrupt), .interrupt_ack(interrupt_ack), .sleep(1'b0),
        .reset(sysreset | rdl), .clk(clk)
    );
    game GAMEPGM (.enable(bram_enable), .address(address), .instruction(instruction), .rdl(rdl), .clk(clk));

    // The keyboard's arrows, held: left, up, right, down.
    wire [3:0] arrow;
    arrows KEYS (.clk(clk), .ps2_clk(PS2Clk), .ps2_data(PS2Data), .held(arrow));

    // Its ports (the course's numbers where it has them).
    reg [ 7:0] box_x = 8'd0, box_y = 8'd0;
    reg [15:0] leds = 16'd0;
    reg [ 4:0] dig0 = 5'd0, dig1 = 5'd0, dig2 = 5'd0, dig3 = 5'd0;
    always @(posedge clk) begin
        case (port_id)
            8'h00: in_port <= {3'b000, db_pbtns[5:1] | {1'b0, arrow}};
            8'h01: in_port <= db_sw[7:0];
            default: in_port <= 8'h00;
        endcase
        if (write_strobe | k_write_strobe) begin
            case (port_id)
                8'h02: leds[7:0] <= out_port;
                8'h03: dig0 <= out_port[4:0];
                8'h04: dig1 <= out_port[4:0];
                8'h05: dig2 <= out_port[4:0];
                8'h06: dig3 <= out_port[4:0];
                8'h08: box_x <= out_port;
                8'h09: box_y <= out_port;
                8'h12: leds[15:8] <= out_port;
                default: ;
            endcase
        end
    end
    assign led = leds;

    sevensegment #(.RESET_POLARITY_LOW(0), .SIMULATE(SIMULATE)) SSB (
        .clk(clk), .reset(sysreset),
        .d7(5'h17), .d6(5'h17), .d5(5'h17), .d4(5'h17), .d3(dig3), .d2(dig2), .d1(dig1), .d0(dig0),
        .dp(8'h00), .seg({dp, seg}), .an(an), .digits_out()
    );

    // The pixel clock: 100 MHz x 10 / 40.
    wire clk25, fb, locked;
    MMCME2_BASE #(.CLKIN1_PERIOD(10.0), .DIVCLK_DIVIDE(1), .CLKFBOUT_MULT_F(10.0), .CLKOUT0_DIVIDE_F(40.0))
        MMCM (.CLKIN1(clk), .CLKFBIN(fb), .CLKFBOUT(fb), .CLKOUT0(clk25), .LOCKED(locked), .RST(1'b0),
              .PWRDWN(1'b0));

    // 640 x 480 at 60 Hz: 800 clocks a line (640, 16, 96, 48), 525 lines a frame (480, 10, 2, 33).
    reg [9:0] col = 10'd0, row = 10'd0;
    always @(posedge clk25) begin
        if (!locked) begin
            col <= 10'd0;
            row <= 10'd0;
        end else if (col == 10'd799) begin
            col <= 10'd0;
            row <= (row == 10'd524) ? 10'd0 : row + 10'd1;
        end else begin
            col <= col + 10'd1;
        end
    end
    // The picture, registered with the syncs of the same pixel: the box white, the rest
    // dark blue with a grey frame around the screen.
    wire visible = col < 10'd640 && row < 10'd480;
    wire [9:0] bx = {box_x, 2'b00}, by = {box_y, 2'b00};
    wire in_box = col >= bx && col < bx + 10'd16 && row >= by && row < by + 10'd16;
    wire edge_px = col < 10'd2 || col >= 10'd638 || row < 10'd2 || row >= 10'd478;
    always @(posedge clk25) begin
        Hsync <= !(col >= 10'd656 && col < 10'd752);
        Vsync <= !(row >= 10'd490 && row < 10'd492);
        {vgaRed, vgaGreen, vgaBlue} <= !visible ? 12'h000 : in_box ? 12'hFFF : edge_px ? 12'h888 : 12'h014;
    end

    // A frame's vertical sync interrupts the CPU (brought into its clock's domain); the
    // acknowledge clears it.
    reg [2:0] vsync_sync = 3'b111;
    always @(posedge clk) begin
        vsync_sync <= {vsync_sync[1:0], Vsync};
        if (sysreset | interrupt_ack) interrupt <= 1'b0;
        else if (vsync_sync[2:1] == 2'b10) interrupt <= 1'b1;
    end
endmodule
