// colorizer.v: world cell and icon to a 12-bit colour (clean-room, from spec botsim.md 12),
// registered on the pixel clock together with the syncs, so colour and syncs leave aligned.
// Colours (4:4:4): floor FFF, line 000, obstruction C22, reserved 29F; icon F80, 04C, FF0.
`timescale 1ns / 1ps
module colorizer (
    input  wire       clock,
    input  wire       video_on,
    input  wire       hsync_in,
    input  wire       vsync_in,
    input  wire [1:0] world_pixel,
    input  wire [1:0] icon,
    output reg  [3:0] red = 4'h0,
    output reg  [3:0] green = 4'h0,
    output reg  [3:0] blue = 4'h0,
    output reg        hsync = 1'b1,
    output reg        vsync = 1'b1
);
    reg [11:0] colour;
    always @(*) begin
        if (!video_on) colour = 12'h000;
        else case (icon)
            2'b01: colour = 12'hF80;
            2'b10: colour = 12'h04C;
            2'b11: colour = 12'hFF0;
            default: case (world_pixel)
                2'b00: colour = 12'hFFF;
                2'b01: colour = 12'h000;
                2'b10: colour = 12'hC22;
                default: colour = 12'h29F;
            endcase
        endcase
    end

    always @(posedge clock) begin
        {red, green, blue} <= colour;
        hsync <= hsync_in;
        vsync <= vsync_in;
    end
endmodule
