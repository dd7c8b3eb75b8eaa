// debounce.v: botsim's stand-in for the course's `debounce`, for designs whose repository
// does not carry it (clean-room, from spec board.md §2; written for botsim). Every input bit
// is taken once it has been stable for 1,600,000 clocks (16 ms at 100 MHz), or 5 with
// SIMULATE = 1. Until then the outputs hold their power-up values: buttons and switches
// released, and the reset button (pbtn_in[0], active low when RESET_POLARITY_LOW) pressed,
// so the design starts in reset as on the board.
//
// The ports are the course's (pbtn_in, switch_in, pbtn_db, swtch_db) and, for designs that
// debounce the reset apart, reset_in/reset_out (reset_out active high). Vectors are wide
// enough for every course board: a narrower connection uses the low bits.
`timescale 1ns / 1ps
module debounce #(
    parameter integer RESET_POLARITY_LOW = 1,
    parameter integer CNTR_WIDTH = 22,
    parameter integer SIMULATE = 0,
    parameter integer SIMULATE_FREQUENCY_CNT = 5
) (
    input  wire        clk,
    input  wire [ 7:0] pbtn_in,
    input  wire [15:0] switch_in,
    input  wire        reset_in,
    output reg  [ 7:0] pbtn_db = {7'd0, RESET_POLARITY_LOW == 0},
    output reg  [15:0] swtch_db = 16'd0,
    output reg         reset_out = 1'b1
);
    localparam integer SETTLE = SIMULATE != 0 ? SIMULATE_FREQUENCY_CNT : 1600000;
    // The raw reset, active high.
    wire        reset_raw = RESET_POLARITY_LOW != 0 ? ~reset_in : reset_in;
    wire [24:0] raw = {reset_raw, pbtn_in, switch_in};
    reg  [24:0] last = 25'd0;
    reg  [20:0] stable = 21'd0;

    always @(posedge clk) begin
        last <= raw;
        if (raw != last) begin
            stable <= 21'd0;
        end else if (stable != SETTLE[20:0]) begin
            stable <= stable + 21'd1;
        end else begin
            {reset_out, pbtn_db, swtch_db} <= raw;
        end
    end
    wire unused_ok = &{1'b0, CNTR_WIDTH[0], 1'b0};
endmodule
