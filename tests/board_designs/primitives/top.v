// top.v: a block built of Xilinx primitives by hand, as the KCPSM6 package's UART macros are
// (clean-room, written for botsim's tests). A 32-stage SRLC32E ring with one bit set pulses
// once every 32 clocks; each pulse steps an 8-bit counter of FDREs whose next value comes
// from two CARRY4s (q + 1); the counter is on LEDs 7-0. LED 15 is a LUT6 of switches 5-0
// (INIT 8000000000000001: on at 000000 and 111111); LED 14 a MUXF7 of switches 6-8.
`timescale 1ns / 1ps
module top (
    input  wire        clk,
    input  wire [15:0] sw,
    output wire [15:0] led
);
    wire pulse, unused_q;
    SRLC32E #(.INIT(32'h00000001)) RING (.Q(unused_q), .Q31(pulse), .A(5'd0), .CE(1'b1), .CLK(clk), .D(pulse));
    wire [7:0] q, next;
    wire [7:0] co;
    CARRY4 LOW (.CO(co[3:0]), .O(next[3:0]), .CI(1'b1), .CYINIT(1'b0), .DI(4'd0), .S(q[3:0]));
    CARRY4 HIGH (.CO(co[7:4]), .O(next[7:4]), .CI(co[3]), .CYINIT(1'b0), .DI(4'd0), .S(q[7:4]));
    genvar i;
    generate
        for (i = 0; i < 8; i = i + 1) begin : count
            FDRE #(.INIT(1'b0)) BIT (.Q(q[i]), .C(clk), .CE(pulse), .D(next[i]), .R(1'b0));
        end
    endgenerate
    wire both;
    LUT6 #(.INIT(64'h8000000000000001)) ENDS (.O(both), .I0(sw[0]), .I1(sw[1]), .I2(sw[2]), .I3(sw[3]), .I4(sw[4]), .I5(sw[5]));
    wire pick;
    MUXF7 PICK (.O(pick), .I0(sw[6]), .I1(sw[7]), .S(sw[8]));
    assign led = {both, pick, 6'd0, q};
endmodule
