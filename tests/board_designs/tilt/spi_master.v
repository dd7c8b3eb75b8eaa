// spi_master.v: an SPI master, mode 0 (clean-room, written for botsim's tests): `start` sends
// `tx` most significant bit first while reading `rx`, SCK at clk / (2 * HALF); MOSI changes
// while SCK is low, MISO is read at SCK's rising edge. `busy` is high until the byte is done.
`timescale 1ns / 1ps
module spi_master #(
    parameter HALF = 25  // 2 MHz at 100 MHz
) (
    input  wire       clk,
    input  wire       start,
    input  wire [7:0] tx,
    output reg  [7:0] rx = 8'd0,
    output reg        busy = 1'b0,
    output reg        sck = 1'b0,
    output wire       mosi,
    input  wire       miso
);
    reg [7:0] shift = 8'd0;
    reg [3:0] bitn = 4'd0;
    reg [7:0] count = 8'd0;
    assign mosi = shift[7];
    always @(posedge clk) begin
        if (!busy) begin
            if (start) begin
                busy <= 1'b1;
                shift <= tx;
                bitn <= 4'd0;
                count <= HALF - 1;
            end
        end else if (count != 8'd0) begin
            count <= count - 8'd1;
        end else begin
            count <= HALF - 1;
            if (!sck) begin
                sck <= 1'b1;
                rx <= {rx[6:0], miso};
            end else begin
                sck <= 1'b0;
                shift <= {shift[6:0], 1'b0};
                bitn <= bitn + 4'd1;
                if (bitn == 4'd7) busy <= 1'b0;
            end
        end
    end
endmodule
