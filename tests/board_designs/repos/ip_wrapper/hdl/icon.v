// icon.v: the bot's icon from a block memory (Icon_Rom: {heading, y, x} -> 2 bits), its pixel
// a pixel clock after the address (clean-room, written for botsim's tests).
`timescale 1ns / 1ps
module icon (
    input  wire       clk,
    input  wire [9:0] pixel_row,
    input  wire [9:0] pixel_column,
    input  wire [7:0] locx,
    input  wire [7:0] locy,
    input  wire [7:0] botinfo,
    output wire [1:0] icon
);
    wire signed [11:0] x = $signed({2'b00, pixel_column}) - $signed({3'b000, locx[6:0], 2'b00}) + 12'sd6;
    wire signed [11:0] y = $signed({2'b00, pixel_row}) - $signed({3'b000, locy[6:0], 2'b00}) + 12'sd6;
    wire on_icon = x >= 0 && x < 16 && y >= 0 && y < 16;
    reg on_q = 1'b0;
    wire [1:0] pixel;
    Icon_Rom ROM (.clka(clk), .addra({botinfo[2:0], y[3:0], x[3:0]}), .douta(pixel));
    always @(posedge clk) on_q <= on_icon;
    assign icon = on_q ? pixel : 2'd0;
endmodule
