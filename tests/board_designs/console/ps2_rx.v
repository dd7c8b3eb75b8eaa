// ps2_rx.v: a PS/2 keyboard receiver (clean-room, written for botsim's tests, from spec
// board.md 7). The clock and data are brought into the clock's domain; at each falling edge
// of the keyboard's clock a bit is read: start (0), eight data bits least significant first,
// odd parity, stop (1). A good frame delivers its byte with a one-clock `valid`; a bad one
// (a wrong start, parity or stop bit) counts an error and is dropped. A frame not finished
// within 2 ms is dropped too. `inhibit` holds the clock low (the host keeps the keyboard
// from sending); the lines are open collector (pulled up on the board).
`timescale 1ns / 1ps
module ps2_rx (
    input  wire       clk,
    input  wire       inhibit,
    inout  wire       ps2_clk,
    inout  wire       ps2_data,
    output reg  [7:0] data = 8'd0,
    output reg        valid = 1'b0,
    output reg  [7:0] errors = 8'd0
);
    assign ps2_clk = inhibit ? 1'b0 : 1'bz;
    assign ps2_data = 1'bz;
    reg [2:0] clk_sync = 3'b111;
    reg [1:0] data_sync = 2'b11;
    reg [3:0] bitn = 4'd0;
    reg [10:0] frame = 11'd0;
    reg [17:0] timeout = 18'd0;
    wire fell = clk_sync[2:1] == 2'b10 && !inhibit;
    wire [10:0] got = {data_sync[1], frame[10:1]};
    always @(posedge clk) begin
        clk_sync <= {clk_sync[1:0], ps2_clk};
        data_sync <= {data_sync[0], ps2_data};
        valid <= 1'b0;
        if (bitn != 4'd0 && timeout == 18'd200000) begin
            bitn <= 4'd0;
            errors <= errors + 8'd1;
        end else if (fell) begin
            frame <= got;
            timeout <= 18'd0;
            if (bitn == 4'd10) begin
                bitn <= 4'd0;
                // got: stop, parity, data 7..0, start
                if (!got[0] && got[10] && ^got[9:1]) begin
                    data <= got[8:1];
                    valid <= 1'b1;
                end else begin
                    errors <= errors + 8'd1;
                end
            end else begin
                bitn <= bitn + 4'd1;
            end
        end else if (bitn != 4'd0) begin
            timeout <= timeout + 18'd1;
        end
    end
endmodule
