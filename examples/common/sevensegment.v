// sevensegment.v: eight multiplexed common-anode digits (clean-room). Digit codes 00-0F
// show 0-F, 10-1F are dark; dp[i] lights digit i's point. Each digit is driven for 2^17
// clocks (1.3 ms at 100 MHz); all outputs are active low.
`timescale 1ns / 1ps
module sevensegment (
    input  wire       clk,
    input  wire       reset,
    input  wire [4:0] d7, d6, d5, d4, d3, d2, d1, d0,
    input  wire [7:0] dp,
    output reg  [6:0] seg = 7'h7F,
    output reg        dp_out = 1'b1,
    output reg  [7:0] an = 8'hFF
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

    // Lit segments, bit 0 = a ... bit 6 = g.
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
            seg <= 7'h7F;
            dp_out <= 1'b1;
        end else begin
            refresh <= refresh + 20'd1;
            an <= ~(8'd1 << which);
            seg <= ~glyph(code);
            dp_out <= ~dp[which];
        end
    end
endmodule
