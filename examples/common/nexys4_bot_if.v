// nexys4_bot_if.v: the team CPU's I/O ports (clean-room), with the course's demo port
// numbers (spec board.md 2), and the interrupt flip-flop: set by upd_sysregs, cleared by
// interrupt_ack.
`timescale 1ns / 1ps
module nexys4_bot_if (
    input  wire        clk,
    input  wire        reset,
    input  wire [ 7:0] port_id,
    input  wire [ 7:0] out_port,
    output reg  [ 7:0] in_port = 8'd0,
    input  wire        write_strobe,
    input  wire        k_write_strobe,
    input  wire        read_strobe,
    output reg         interrupt = 1'b0,
    input  wire        interrupt_ack,
    input  wire [ 4:0] btns,
    input  wire [15:0] switches,
    output reg  [15:0] leds = 16'd0,
    output reg  [ 4:0] dig7 = 5'h17, dig6 = 5'h17, dig5 = 5'h17, dig4 = 5'h17,
    output reg  [ 4:0] dig3 = 5'h17, dig2 = 5'h17, dig1 = 5'h17, dig0 = 5'h17,
    output reg  [ 7:0] decpts = 8'd0,
    output reg  [ 7:0] motctl = 8'd0,
    input  wire [ 7:0] locx, locy, botinfo, sensors, lmdist, rmdist,
    input  wire        upd_sysregs
);
    wire unused_ok = &{1'b0, read_strobe, 1'b0};

    always @(posedge clk) begin
        case (port_id)
            8'h00: in_port <= {3'b000, btns};
            8'h01: in_port <= switches[7:0];
            8'h0A: in_port <= locx;
            8'h0B: in_port <= locy;
            8'h0C: in_port <= botinfo;
            8'h0D: in_port <= sensors;
            8'h0E: in_port <= lmdist;
            8'h0F: in_port <= rmdist;
            8'h11: in_port <= switches[15:8];
            default: in_port <= 8'h00;
        endcase
    end

    always @(posedge clk) begin
        if (reset) begin
            leds <= 16'd0;
            motctl <= 8'd0;
        end else if (write_strobe | k_write_strobe) begin
            case (port_id)
                8'h02: leds[7:0] <= out_port;
                8'h03: dig0 <= out_port[4:0];
                8'h04: dig1 <= out_port[4:0];
                8'h05: dig2 <= out_port[4:0];
                8'h06: dig3 <= out_port[4:0];
                8'h07: decpts[3:0] <= out_port[3:0];
                8'h09: motctl <= out_port;
                8'h12: leds[15:8] <= out_port;
                8'h13: dig4 <= out_port[4:0];
                8'h14: dig5 <= out_port[4:0];
                8'h15: dig6 <= out_port[4:0];
                8'h16: dig7 <= out_port[4:0];
                8'h17: decpts[7:4] <= out_port[3:0];
                default: ;
            endcase
        end
    end

    always @(posedge clk) begin
        if (reset) interrupt <= 1'b0;
        else if (interrupt_ack) interrupt <= 1'b0;
        else if (upd_sysregs) interrupt <= 1'b1;
    end
endmodule
