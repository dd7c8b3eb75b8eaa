// sevensegment.v: the course's `sevensegment` as spec board.md §2.1 states it (clean-room,
// written for botsim from that text), for designs whose repository does not carry it.
//
// Eight multiplexed common-anode digits, all outputs active low. A free-running wrap counter
// `clk_cnt` (cleared by reset) ticks every top_cnt + 1 clocks (200,000 at 100 MHz, or 6 with
// SIMULATE = 1). At each tick the anodes rotate one digit (1111_1110 -> 1111_1101 -> ... ->
// 0111_1111 -> back; any other value -> digit 0). Every clock, each digit's pattern is
// registered from its 5-bit code by a `sevensegment_digit`, and `seg` registers the pattern
// of the digit whose anode is low (all eight bits 0, every segment lit, if `an` holds another
// value). seg[7] is the point (~dp[i]), seg[6:0] = g..a. digits_out is never assigned.
//
// `reset` is active low when RESET_POLARITY_LOW, else active high (board.md names the
// parameter, not its effect: this reading is botsim's). Registers power up 0, as an FPGA
// configures registers without an initial value.
//
// DIGITS is botsim's, not the course's: the Nexys3 version (Winter 2014) walks four digits
// (1111_1110 .. 1111_0111), otherwise the same; botsim sets it to 4 for an instance that
// connects none of d4..d7.
`timescale 1ns / 1ps
module sevensegment #(
    parameter integer CLK_FREQUENCY_HZ       = 100_000_000,
    parameter integer REFRESH_FREQUENCY_HZ   = 500,
    parameter integer RESET_POLARITY_LOW     = 1,
    parameter integer CNTR_WIDTH             = 32,
    parameter integer SIMULATE               = 0,
    parameter integer SIMULATE_FREQUENCY_CNT = 5,
    parameter integer DIGITS                 = 8
) (
    input  wire        clk,
    input  wire        reset,
    input  wire [ 4:0] d0, d1, d2, d3, d4, d5, d6, d7,
    input  wire [ 7:0] dp,
    output reg  [ 7:0] seg = 8'h00,
    output reg  [ 7:0] an = 8'h00,
    output wire [63:0] digits_out
);
    localparam [CNTR_WIDTH-1:0] TOP_CNT = SIMULATE != 0 ? SIMULATE_FREQUENCY_CNT
                                        : CLK_FREQUENCY_HZ / REFRESH_FREQUENCY_HZ - 1;

    wire reset_in = RESET_POLARITY_LOW != 0 ? ~reset : reset;
    reg  [CNTR_WIDTH-1:0] clk_cnt = {CNTR_WIDTH{1'b0}};
    wire tick = clk_cnt == TOP_CNT;

    always @(posedge clk) begin
        if (reset_in) clk_cnt <= {CNTR_WIDTH{1'b0}};
        else clk_cnt <= tick ? {CNTR_WIDTH{1'b0}} : clk_cnt + 1'b1;
    end

    // The next digit's anode: the one after the lit one, back to digit 0 after the last.
    reg [7:0] next_an;
    integer j;
    always @(*) begin
        next_an = 8'b1111_1110;
        for (j = 0; j < DIGITS - 1; j = j + 1)
            if (an == ~(8'd1 << j)) next_an = ~(8'd1 << (j + 1));
    end
    always @(posedge clk) begin
        if (tick) an <= next_an;
    end

    wire [7:0] p0, p1, p2, p3, p4, p5, p6, p7;
    sevensegment_digit D0 (.clk(clk), .code(d0), .point(dp[0]), .pattern(p0));
    sevensegment_digit D1 (.clk(clk), .code(d1), .point(dp[1]), .pattern(p1));
    sevensegment_digit D2 (.clk(clk), .code(d2), .point(dp[2]), .pattern(p2));
    sevensegment_digit D3 (.clk(clk), .code(d3), .point(dp[3]), .pattern(p3));
    sevensegment_digit D4 (.clk(clk), .code(d4), .point(dp[4]), .pattern(p4));
    sevensegment_digit D5 (.clk(clk), .code(d5), .point(dp[5]), .pattern(p5));
    sevensegment_digit D6 (.clk(clk), .code(d6), .point(dp[6]), .pattern(p6));
    sevensegment_digit D7 (.clk(clk), .code(d7), .point(dp[7]), .pattern(p7));

    always @(posedge clk) begin
        case (an)
            8'b1111_1110: seg <= p0;
            8'b1111_1101: seg <= p1;
            8'b1111_1011: seg <= p2;
            8'b1111_0111: seg <= p3;
            8'b1110_1111: seg <= p4;
            8'b1101_1111: seg <= p5;
            8'b1011_1111: seg <= p6;
            8'b0111_1111: seg <= p7;
            default:      seg <= 8'h00;
        endcase
    end

    assign digits_out = 64'd0;
    wire unused_ok = &{1'b0, CNTR_WIDTH[0], 1'b0};
endmodule

// One digit's segments from its code, registered every clock (active low; pattern[7] the
// point): codes 0-15 the hexadecimal glyphs (b and d lower case), 16-22 segment a..g alone,
// 24 H, 25 L, 26 abcefg, 27 ef, 28 eg; 23 and 29-31 blank.
module sevensegment_digit (
    input  wire       clk,
    input  wire [4:0] code,
    input  wire       point,
    output reg  [7:0] pattern = 8'h00
);
    reg [6:0] lit;  // bit 0 = a ... bit 6 = g
    always @(*) begin
        case (code)
            5'd0:  lit = 7'b0111111;
            5'd1:  lit = 7'b0000110;
            5'd2:  lit = 7'b1011011;
            5'd3:  lit = 7'b1001111;
            5'd4:  lit = 7'b1100110;
            5'd5:  lit = 7'b1101101;
            5'd6:  lit = 7'b1111101;
            5'd7:  lit = 7'b0000111;
            5'd8:  lit = 7'b1111111;
            5'd9:  lit = 7'b1101111;
            5'd10: lit = 7'b1110111;
            5'd11: lit = 7'b1111100;
            5'd12: lit = 7'b0111001;
            5'd13: lit = 7'b1011110;
            5'd14: lit = 7'b1111001;
            5'd15: lit = 7'b1110001;
            5'd16: lit = 7'b0000001;
            5'd17: lit = 7'b0000010;
            5'd18: lit = 7'b0000100;
            5'd19: lit = 7'b0001000;
            5'd20: lit = 7'b0010000;
            5'd21: lit = 7'b0100000;
            5'd22: lit = 7'b1000000;
            5'd24: lit = 7'b1110110;
            5'd25: lit = 7'b0111000;
            5'd26: lit = 7'b1110111;
            5'd27: lit = 7'b0110000;
            5'd28: lit = 7'b1010000;
            default: lit = 7'b0000000;
        endcase
    end
    always @(posedge clk) pattern <= {~point, ~lit};
endmodule
