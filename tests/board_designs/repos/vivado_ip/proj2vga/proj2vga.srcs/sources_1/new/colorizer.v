// colorizer.v: world cell and icon to a 12-bit colour through the `palette` ROM (a Block
// Memory Generator core, read latency 1: the colour is registered as the syncs are).
`timescale 1ns / 1ps
module colorizer (
    input  wire       clock,
    input  wire       video_on,
    input  wire       hsync_in,
    input  wire       vsync_in,
    input  wire [1:0] world_pixel,
    input  wire [1:0] icon,
    output wire [3:0] red,
    output wire [3:0] green,
    output wire [3:0] blue,
    output reg        hsync = 1'b1,
    output reg        vsync = 1'b1
);
    wire [11:0] colour;
    palette PALETTE (.clka(clock), .addra({video_on, icon, world_pixel}), .douta(colour));
    assign {red, green, blue} = colour;
    always @(posedge clock) begin
        hsync <= hsync_in;
        vsync <= vsync_in;
    end
endmodule
