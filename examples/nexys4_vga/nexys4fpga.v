// nexys4fpga.v: botsim's example of a course Project 2 design with the VGA display
// (clean-room, written for botsim from spec board.md and botsim.md 12): the system in
// ../common, plus a Clocking-Wizard-style 25 MHz pixel clock, a display timing generator,
// the world read through the bot's video port at 4 x 4 pixels per cell, the bot's icon and a
// colorizer driving the Nexys4's 12-bit VGA pins.
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
    output wire [ 7:0] JA,
    output wire [ 3:0] vgaRed,
    output wire [ 3:0] vgaGreen,
    output wire [ 3:0] vgaBlue,
    output wire        Hsync,
    output wire        Vsync
);
    wire [9:0] pixel_row, pixel_column;
    wire [1:0] world_pixel, icon_pixel;
    wire [7:0] locx, locy, botinfo;
    wire       clk25, locked, video_on, hsync, vsync;

    proj2_system #(.SIMULATE(SIMULATE)) SYS (
        .clk(clk), .btnCpuReset(btnCpuReset), .btnC(btnC), .btnU(btnU), .btnD(btnD), .btnL(btnL),
        .btnR(btnR), .sw(sw), .led(led), .seg(seg), .dp(dp), .an(an), .JA(JA),
        .vid_row({2'b00, pixel_row[9:2]}), .vid_col({2'b00, pixel_column[9:2]}),
        .vid_pixel_out(world_pixel), .locx(locx), .locy(locy), .botinfo(botinfo)
    );

    clk_wiz_0 CLKGEN (.clk_in1(clk), .clk_out1(clk25), .reset(1'b0), .locked(locked));

    dtg DTG (
        .clock(clk25), .rst(~locked), .horiz_sync(hsync), .vert_sync(vsync), .video_on(video_on),
        .pixel_row(pixel_row), .pixel_column(pixel_column)
    );

    icon ICON (
        .pixel_row(pixel_row), .pixel_column(pixel_column), .locx(locx), .locy(locy),
        .botinfo(botinfo), .icon(icon_pixel)
    );

    // The world pixel arrives 2 bot clocks (20 ns) after the address, within the pixel clock:
    // the colorizer registers it with the icon and the syncs of the same pixel.
    colorizer COLOR (
        .clock(clk25), .video_on(video_on), .hsync_in(hsync), .vsync_in(vsync),
        .world_pixel(world_pixel), .icon(icon_pixel),
        .red(vgaRed), .green(vgaGreen), .blue(vgaBlue), .hsync(Hsync), .vsync(Vsync)
    );
endmodule
