// top.v: the board's idle-high lines as a design sees them (clean-room, for botsim's tests,
// from spec board.md 7): the USB-UART's RsRx into the FPGA and the PS/2 clock and data, open
// collector with pull-ups, shown on LEDs 2-0; switch 0 pulls the PS/2 clock low, as a host
// inhibits the keyboard.
`timescale 1ns / 1ps
module top (
    input  wire        clk,
    input  wire [15:0] sw,
    output wire [15:0] led,
    input  wire        RsRx,
    output wire        RsTx,
    inout  wire        PS2_CLK,
    inout  wire        PS2_DATA
);
    assign PS2_CLK = sw[0] ? 1'b0 : 1'bz;
    assign PS2_DATA = 1'bz;
    assign RsTx = 1'b1;
    reg [2:0] lines = 3'd0;
    always @(posedge clk) lines <= {RsRx, PS2_DATA, PS2_CLK};
    assign led = {13'd0, lines};
endmodule
