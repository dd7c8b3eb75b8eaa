// timed.v: a board design whose LED 0 lights when the simulation time reaches 30 ms (test
// design for botsim board: a design that reads $time does not repeat itself, whatever its
// flops say, so the fast-forward must stay off for it).
`timescale 1ns / 1ps
module timed (
    input  wire        clk,
    input  wire        btnCpuReset,
    output wire [15:0] led
);
    reg late = 1'b0;
    always @(posedge clk)
        if ($time >= 64'd30_000_000) late <= 1'b1;
    assign led = {15'd0, late};

    // The design must hold a bot.
    bot ROJOBOT (.MotCtl_in(8'h00), .vid_row(10'd0), .vid_col(10'd0), .clk(clk), .reset(~btnCpuReset));
endmodule
