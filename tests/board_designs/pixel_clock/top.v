// top.v: tests/board_designs/phases (a KCPSM6 waiting beside a display refresh counter of
// 2^16 clocks) with a 25 MHz pixel clock from the VGA example's Clocking Wizard driving a
// "frame" counter of 1,000 pixel clocks (test design for botsim board's fast-forward; built
// with ../phases and examples/nexys4_vga/clk_wiz_0.v). The two counters repeat together only
// every 8.2 M clocks, more than a sample. With FEEDBACK 0 the frame counter drives VGA pins
// alone, which a run without frames does not record: the fast-forward compares and puts
// back the rest, and skips. With FEEDBACK 1 each frame also toggles LED 15, so the pixel
// clock drives what the run records: it runs, and the fast-forward compares where it is in
// its period too and moves the pixel counter on between its wraps.
`timescale 1ns / 1ps
module pixel_top #(
    parameter FEEDBACK = 0
) (
    input  wire        clk,
    input  wire        btnCpuReset,
    output wire [ 7:0] an,
    output wire [ 6:0] seg,
    output wire [15:0] led,
    output wire [ 3:0] vgaRed,
    output wire        Hsync
);
    wire [15:0] count_led;
    top phases (.clk(clk), .btnCpuReset(btnCpuReset), .an(an), .seg(seg), .led(count_led));

    wire clk25, locked;
    clk_wiz_0 CLKGEN (.clk_in1(clk), .clk_out1(clk25), .reset(1'b0), .locked(locked));

    reg [9:0] pixel = 10'd0;
    reg       frame = 1'b0;
    always @(posedge clk25) begin
        if (pixel == 10'd999) begin
            pixel <= 10'd0;
            frame <= ~frame;
        end else begin
            pixel <= pixel + 10'd1;
        end
    end
    assign vgaRed = pixel[3:0];
    assign Hsync = pixel[9];
    assign led = {FEEDBACK != 0 ? frame : 1'b0, count_led[14:0]};
    wire unused_ok = &{1'b0, locked, count_led[15], 1'b0};
endmodule
