// debounce.v: debounced push buttons, switches and reset (clean-room). A change is taken once
// it has been stable for 2^20 clocks (about 10 ms at 100 MHz); SIMULATE = 1 shortens that to
// 4 clocks so simulations start at once.
`timescale 1ns / 1ps
module debounce #(
    parameter RESET_POLARITY_LOW = 1,
    parameter SIMULATE = 0
) (
    input  wire        clk,
    input  wire [ 4:0] pbtn_in,
    input  wire [15:0] switch_in,
    input  wire        reset_in,
    output reg  [ 4:0] pbtn_db = 5'd0,
    output reg  [15:0] swtch_db = 16'd0,
    output reg         reset_out = 1'b1
);
    localparam integer BITS = SIMULATE ? 2 : 20;
    wire [21:0] raw = {reset_in ^ (RESET_POLARITY_LOW != 0), pbtn_in, switch_in};
    reg  [21:0] last = 22'd0;
    reg  [BITS-1:0] stable = {BITS{1'b0}};

    always @(posedge clk) begin
        last <= raw;
        if (raw != last) begin
            stable <= {BITS{1'b0}};
        end else if (stable != {BITS{1'b1}}) begin
            stable <= stable + 1'b1;
        end else begin
            {reset_out, pbtn_db, swtch_db} <= raw;
        end
    end
endmodule
