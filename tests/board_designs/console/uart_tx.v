// uart_tx.v: an 8N1 transmitter (clean-room, written for botsim's tests): `start` with the
// byte in `data` sends it (start bit, data least significant first, stop bit), `busy` high
// until the stop bit ends.
`timescale 1ns / 1ps
module uart_tx #(
    parameter CLKS_PER_BIT = 868
) (
    input  wire       clk,
    input  wire       start,
    input  wire [7:0] data,
    output reg        tx = 1'b1,
    output reg        busy = 1'b0
);
    reg [3:0] bitn = 4'd0;
    reg [15:0] count = 16'd0;
    reg [9:0] frame = 10'h3FF;
    always @(posedge clk) begin
        if (!busy) begin
            if (start) begin
                busy <= 1'b1;
                frame <= {1'b1, data, 1'b0};
                bitn <= 4'd0;
                count <= CLKS_PER_BIT - 1;
                tx <= 1'b0;
            end
        end else if (count != 16'd0) begin
            count <= count - 16'd1;
        end else if (bitn == 4'd9) begin
            busy <= 1'b0;
        end else begin
            count <= CLKS_PER_BIT - 1;
            bitn <= bitn + 4'd1;
            tx <= frame[bitn + 4'd1];
        end
    end
endmodule
