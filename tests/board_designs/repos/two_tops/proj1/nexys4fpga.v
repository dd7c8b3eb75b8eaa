// nexys4fpga.v: Project 1's top (clean-room, written for botsim's tests): the switches on
// the LEDs and a counter on the display's anodes; no bot.
`timescale 1ns / 1ps
module nexys4fpga (
    input  wire        clk,
    input  wire        btnCpuReset,
    input  wire [15:0] sw,
    output wire [15:0] led,
    output wire [ 6:0] seg,
    output wire        dp,
    output wire [ 7:0] an
);
    reg [19:0] count = 20'd0;
    always @(posedge clk) count <= btnCpuReset ? count + 20'd1 : 20'd0;
    assign led = sw;
    assign an = ~(8'd1 << count[19:17]);
    assign seg = 7'b1000000;
    assign dp = 1'b1;
endmodule
