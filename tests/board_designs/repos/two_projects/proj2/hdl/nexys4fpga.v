// nexys4fpga.v: Project 2 with the accelerometer's X reading on LED[15:12] and a switch
// pattern from a ROM on LED[11:8] (clean-room, written for botsim's tests).
`timescale 1ns / 1ps
module nexys4fpga #(parameter SIMULATE = 0) (
    input  wire        clk,
    input  wire        btnCpuReset,
    input  wire        btnC, btnU, btnD, btnL, btnR,
    input  wire [15:0] sw,
    output wire [15:0] led,
    output wire [ 6:0] seg,
    output wire        dp,
    output wire [ 7:0] an
);
    wire [15:0] sys_led;
    proj2_system #(.SIMULATE(SIMULATE)) SYS (
        .clk(clk), .btnCpuReset(btnCpuReset), .btnC(btnC), .btnU(btnU), .btnD(btnD), .btnL(btnL),
        .btnR(btnR), .sw(sw), .led(sys_led), .seg(seg), .dp(dp), .an(an), .JA(),
        .vid_row(10'd0), .vid_col(10'd0), .vid_pixel_out(), .locx(), .locy(), .botinfo()
    );

    wire [11:0] accel_x;
    wire        accel_ready;
    AccelCtl #(.SYSCLK_FREQUENCY_HZ(100000000)) ACCEL (
        .SYSCLK(clk), .RESET(~btnCpuReset), .ACCEL_X(accel_x), .Data_Ready(accel_ready)
    );

    wire [3:0] pattern;
    led_rom PATTERN (.clka(clk), .addra(sw[3:0]), .douta(pattern));

    assign led = {accel_x[3:0], pattern, sys_led[7:0]};
endmodule
