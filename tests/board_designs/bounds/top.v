// top.v: a counter compared with a register that does not hold (clean-room, written for
// botsim's tests): `limit` alternates every clock between 60,000 and 30,001, and `count`
// (from 0) meets it at 30,001, where it wraps and LED 0 toggles. A fast-forward that took the
// register for a constant (its value at a mark, 60,000) would move the counter past 30,001.
// LED 1 shows switch 0.
`timescale 1ns / 1ps
module top (
    input  wire        clk,
    input  wire [15:0] sw,
    output wire [15:0] led
);
    reg [19:0] limit = 20'd60000;
    always @(posedge clk) limit <= (limit == 20'd60000) ? 20'd30001 : 20'd60000;
    reg [19:0] count = 20'd0;
    reg toggle = 1'b0;
    always @(posedge clk) begin
        if (count == limit) begin
            count <= 20'd0;
            toggle <= !toggle;
        end else begin
            count <= count + 20'd1;
        end
    end
    assign led = {14'd0, sw[0], toggle};
endmodule
