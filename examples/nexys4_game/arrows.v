// arrows.v: the keyboard's arrow keys as held buttons (clean-room, written for botsim's tests
// from spec board.md 7). The PS/2 clock's falling edges (seen on the board's clock) shift the
// data line into an 11-bit frame; a frame with a 0 start bit, odd parity and a 1 stop bit is
// a scan code. E0 marks the next code extended, F0 the next a release: E0 75 / E0 F0 75 press
// and release up, and so down (72), left (6B) and right (74). Other keys change nothing. The
// receiver only listens (the lines are left to the keyboard).
`timescale 1ns / 1ps
module arrows (
    input  wire       clk,
    input  wire       ps2_clk,
    input  wire       ps2_data,
    output reg  [3:0] held = 4'd0   // left, up, right, down
);
    reg [3:0] clk_hist = 4'hF;
    reg [10:0] shift = 11'h7FF;
    reg [3:0] bits = 4'd0;
    reg extended = 1'b0, breaking = 1'b0;
    wire falling = clk_hist[3:2] == 2'b10;
    wire [10:0] frame = {ps2_data, shift[10:1]};
    wire [7:0] code = frame[8:1];
    wire good = !frame[0] && frame[10] && ^frame[9:1];
    always @(posedge clk) begin
        clk_hist <= {clk_hist[2:0], ps2_clk};
        if (falling) begin
            shift <= frame;
            if (bits == 4'd10) begin
                bits <= 4'd0;
                if (good) begin
                    if (code == 8'hE0) begin
                        extended <= 1'b1;
                    end else if (code == 8'hF0) begin
                        breaking <= 1'b1;
                    end else begin
                        if (extended) begin
                            case (code)
                                8'h6B: held[3] <= !breaking;
                                8'h75: held[2] <= !breaking;
                                8'h74: held[1] <= !breaking;
                                8'h72: held[0] <= !breaking;
                                default: ;
                            endcase
                        end
                        extended <= 1'b0;
                        breaking <= 1'b0;
                    end
                end
            end else begin
                bits <= bits + 4'd1;
            end
        end
    end
endmodule
