// debounce.v: the course's `debounce` as spec board.md §2.1 states it (clean-room, written for
// botsim from that text), for designs whose repository does not carry it.
//
// A free-running wrap counter `db_count` ticks every top_cnt + 1 clocks (400,000 at 100 MHz,
// or 6 with SIMULATE = 1) and never stops. At each tick every input bit is shifted into its
// own 4-bit shift register, entering at the top (bit 3), so a change takes four ticks to fill
// it. Every clock an output bit becomes 0 when its shift register is 0000 and 1 when it is
// 1111, else keeps its value.
//
// Power-up: every output 0, every shift register 0000 but the reset button's (pbtn_in[0]),
// which is 0001 when RESET_POLARITY_LOW: its debounced output reads "pressed" (0) until four
// ticks of a released button.
`timescale 1ns / 1ps
module debounce #(
    parameter integer CLK_FREQUENCY_HZ       = 100_000_000,
    parameter integer DEBOUNCE_FREQUENCY_HZ  = 250,
    parameter integer RESET_POLARITY_LOW     = 1,
    parameter integer CNTR_WIDTH             = 32,
    parameter integer SIMULATE               = 0,
    parameter integer SIMULATE_FREQUENCY_CNT = 5
) (
    input  wire        clk,
    input  wire [ 5:0] pbtn_in,
    input  wire [15:0] switch_in,
    output reg  [ 5:0] pbtn_db = 6'd0,
    output reg  [15:0] swtch_db = 16'd0
);
    localparam [CNTR_WIDTH-1:0] TOP_CNT = SIMULATE != 0 ? SIMULATE_FREQUENCY_CNT
                                        : CLK_FREQUENCY_HZ / DEBOUNCE_FREQUENCY_HZ - 1;
    localparam integer N = 22;  // 6 buttons, 16 switches

    reg  [CNTR_WIDTH-1:0] db_count = {CNTR_WIDTH{1'b0}};
    wire                  tick = db_count == TOP_CNT;
    wire [N-1:0]          in = {switch_in, pbtn_in};
    wire [N-1:0]          out = {swtch_db, pbtn_db};
    reg  [3:0]            shift [0:N-1];
    reg  [N-1:0]          next;

    integer i;
    initial begin
        for (i = 0; i < N; i = i + 1) shift[i] = 4'b0000;
        if (RESET_POLARITY_LOW != 0) shift[0] = 4'b0001;
    end

    always @(posedge clk) begin
        db_count <= tick ? {CNTR_WIDTH{1'b0}} : db_count + 1'b1;
    end

    // Each bit's shift register and output.
    always @(*) begin
        for (i = 0; i < N; i = i + 1)
            next[i] = shift[i] == 4'b0000 ? 1'b0 : shift[i] == 4'b1111 ? 1'b1 : out[i];
    end
    always @(posedge clk) begin
        for (i = 0; i < N; i = i + 1)
            if (tick) shift[i] <= {in[i], shift[i][3:1]};
        {swtch_db, pbtn_db} <= next;
    end
endmodule
