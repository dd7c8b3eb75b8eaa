// nexys4fpga.v: a course-style design with a 1024 x 768 VGA display (clean-room, written for
// botsim from spec board.md 1: 1344 x 806 at 60 Hz, syncs active low), for the tests that
// see botsim's VGA capture and the live board at that mode. The system of examples/common
// (the team CPU, the display, the bot), a 65 MHz pixel clock from an MMCM (100 MHz x 10 /
// 15.375 = 65.04 MHz), a timing generator, and a picture: colour bands from the row and
// column, and a white 8 x 6 box where the bot is (LocX x 8, LocY x 6).
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
    output reg  [ 3:0] vgaRed = 4'd0,
    output reg  [ 3:0] vgaGreen = 4'd0,
    output reg  [ 3:0] vgaBlue = 4'd0,
    output reg         Hsync = 1'b1,
    output reg         Vsync = 1'b1
);
    wire [7:0] locx, locy, botinfo;
    wire       clk65, fb, locked;

    proj2_system #(.SIMULATE(SIMULATE)) SYS (
        .clk(clk), .btnCpuReset(btnCpuReset), .btnC(btnC), .btnU(btnU), .btnD(btnD), .btnL(btnL),
        .btnR(btnR), .sw(sw), .led(led), .seg(seg), .dp(dp), .an(an), .JA(JA),
        .vid_row(8'd0), .vid_col(8'd0), .vid_pixel_out(), .locx(locx), .locy(locy), .botinfo(botinfo)
    );

    MMCME2_BASE #(.CLKIN1_PERIOD(10.0), .DIVCLK_DIVIDE(1), .CLKFBOUT_MULT_F(10.0), .CLKOUT0_DIVIDE_F(15.375))
        MMCM (.CLKIN1(clk), .CLKFBIN(fb), .CLKFBOUT(fb), .CLKOUT0(clk65), .LOCKED(locked), .RST(1'b0),
              .PWRDWN(1'b0));

    // 1344 clocks a line (1024 visible, 24 front porch, 136 sync, 160 back porch), 806 lines
    // a frame (768, 3, 6, 29).
    reg [10:0] col = 11'd0;
    reg [9:0]  row = 10'd0;
    always @(posedge clk65) begin
        if (!locked) begin
            col <= 11'd0;
            row <= 10'd0;
        end else if (col == 11'd1343) begin
            col <= 11'd0;
            row <= (row == 10'd805) ? 10'd0 : row + 10'd1;
        end else begin
            col <= col + 11'd1;
        end
    end

    // The picture, registered with the syncs of the same pixel.
    wire visible = col < 11'd1024 && row < 10'd768;
    wire [10:0] box_x = {locx, 3'b000};
    wire [10:0] box_y = {locy, 3'b000} - {2'b00, locy, 1'b0};
    wire in_box = col >= box_x && col < box_x + 11'd8 && {1'b0, row} >= box_y && {1'b0, row} < box_y + 11'd6;
    always @(posedge clk65) begin
        Hsync <= !(col >= 11'd1048 && col < 11'd1184);
        Vsync <= !(row >= 10'd771 && row < 10'd777);
        {vgaRed, vgaGreen, vgaBlue} <= !visible ? 12'h000 : in_box ? 12'hFFF : {col[9:6], row[9:6], 4'h3};
    end
endmodule
