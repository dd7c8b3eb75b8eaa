// sevensegment.v: botsim's stand-in for the course's `sevensegment`, for designs whose
// repository does not carry it (clean-room, from spec board.md §1-§2; written for botsim).
// Eight multiplexed common-anode digits: d0..d7 are 5-bit codes (00-0F show 0-F, 10-1F are
// dark), dp[i] lights digit i's point; each digit is driven for 2^17 clocks (1.3 ms at
// 100 MHz). All outputs are active low: an[7:0], seg[6:0] = g..a with the point in seg[7]
// (and on dp_out). digits_out shows the low nibbles of d7..d0 for simulation.
`timescale 1ns / 1ps
module sevensegment #(
    parameter integer RESET_POLARITY_LOW = 1,
    parameter integer SIMULATE = 0
) (
    input  wire        clk,
    input  wire        reset,
    input  wire [ 4:0] d7, d6, d5, d4, d3, d2, d1, d0,
    input  wire [ 7:0] dp,
    output reg  [ 7:0] seg = 8'hFF,
    output wire        dp_out,
    output reg  [ 7:0] an = 8'hFF,
    output wire [31:0] digits_out
);
    reg [19:0] refresh = 20'd0;
    wire [2:0] which = refresh[19:17];
    reg [4:0] code;

    always @(*) begin
        case (which)
            3'd0: code = d0;
            3'd1: code = d1;
            3'd2: code = d2;
            3'd3: code = d3;
            3'd4: code = d4;
            3'd5: code = d5;
            3'd6: code = d6;
            default: code = d7;
        endcase
    end

    // Lit segments, bit 0 = a ... bit 6 = g (board.md §1's glyphs).
    function [6:0] glyph(input [4:0] c);
        case (c)
            5'h00: glyph = 7'b0111111;
            5'h01: glyph = 7'b0000110;
            5'h02: glyph = 7'b1011011;
            5'h03: glyph = 7'b1001111;
            5'h04: glyph = 7'b1100110;
            5'h05: glyph = 7'b1101101;
            5'h06: glyph = 7'b1111101;
            5'h07: glyph = 7'b0000111;
            5'h08: glyph = 7'b1111111;
            5'h09: glyph = 7'b1101111;
            5'h0A: glyph = 7'b1110111;
            5'h0B: glyph = 7'b1111100;
            5'h0C: glyph = 7'b0111001;
            5'h0D: glyph = 7'b1011110;
            5'h0E: glyph = 7'b1111001;
            5'h0F: glyph = 7'b1110001;
            default: glyph = 7'b0000000;
        endcase
    endfunction

    always @(posedge clk) begin
        if (reset) begin
            refresh <= 20'd0;
            an <= 8'hFF;
            seg <= 8'hFF;
        end else begin
            refresh <= refresh + 20'd1;
            an <= ~(8'd1 << which);
            seg <= {~dp[which], ~glyph(code)};
        end
    end
    assign dp_out = seg[7];
    assign digits_out = {d7[3:0], d6[3:0], d5[3:0], d4[3:0], d3[3:0], d2[3:0], d1[3:0], d0[3:0]};
    wire unused_ok = &{1'b0, RESET_POLARITY_LOW[0], SIMULATE[0], 1'b0};
endmodule
