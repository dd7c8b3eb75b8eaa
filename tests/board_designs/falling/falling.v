// falling.v: a board design whose LEDs count the board clock's falling edges (test design for
// botsim board: a design with logic on the falling edge must have its falling edges
// evaluated, whereas most designs need their rising edges only).
`timescale 1ns / 1ps
module falling (
    input  wire        clk,
    input  wire        btnCpuReset,
    output wire [15:0] led
);
    reg [15:0] falls = 16'd0;
    always @(negedge clk) falls <= falls + 16'd1;
    assign led = falls;

    // The design must hold a bot.
    bot ROJOBOT (.MotCtl_in(8'h00), .vid_row(10'd0), .vid_col(10'd0), .clk(clk), .reset(~btnCpuReset));
endmodule
