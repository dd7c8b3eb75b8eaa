// uart_rx.v: an 8N1 receiver (clean-room, written for botsim's tests). The line is brought
// into the clock's domain; a falling edge while idle starts a frame, each bit is read at its
// middle (CLKS_PER_BIT clocks apart); a frame whose stop bit is 1 delivers its byte with a
// one-clock `valid`, one whose stop bit is 0 counts a framing error instead.
`timescale 1ns / 1ps
module uart_rx #(
    parameter CLKS_PER_BIT = 868  // 115200 baud at 100 MHz
) (
    input  wire       clk,
    input  wire       rx,
    output reg  [7:0] data = 8'd0,
    output reg        valid = 1'b0,
    output reg  [7:0] errors = 8'd0
);
    reg [2:0] sync = 3'b111;
    reg busy = 1'b0;
    reg [3:0] bitn = 4'd0;
    reg [15:0] count = 16'd0;
    reg [7:0] shift = 8'd0;
    wire line = sync[2];
    always @(posedge clk) begin
        sync <= {sync[1:0], rx};
        valid <= 1'b0;
        if (!busy) begin
            if (!line) begin
                busy <= 1'b1;
                bitn <= 4'd0;
                count <= CLKS_PER_BIT / 2;
            end
        end else if (count != 16'd0) begin
            count <= count - 16'd1;
        end else begin
            count <= CLKS_PER_BIT - 1;
            bitn <= bitn + 4'd1;
            if (bitn == 4'd0) begin
                if (line) busy <= 1'b0;  // a glitch, not a start bit
            end else if (bitn <= 4'd8) begin
                shift <= {line, shift[7:1]};
            end else begin
                busy <= 1'b0;
                if (line) begin
                    data <= shift;
                    valid <= 1'b1;
                end else begin
                    errors <= errors + 8'd1;
                end
            end
        end
    end
endmodule
