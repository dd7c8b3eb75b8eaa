// kcpsm6_harness.v: the CPU test harness for lock-step testing against the ISS.
//
// kcpsm6 with a 4K program memory (a one-cycle BRAM read, loaded from Rust) and an input-port
// model: a registered mux like BotSim's world_if, returning inputs[port_id] XOR the low byte
// of a free-running cycle counter. The counter makes the exact sampling edge of every INPUT
// visible in the value read. Reset, sleep and interrupt are driven from Rust every cycle.
`timescale 1ns / 1ps
module kcpsm6_harness #(
    parameter integer SPM_SIZE = 64,
    parameter [7:0] HWBUILD = 8'h00,
    parameter [11:0] VECTOR = 12'h3FF
) (
    input  wire        clk,
    input  wire        reset,
    input  wire        sleep,
    input  wire        interrupt,
    output wire [11:0] address,
    output reg  [17:0] instruction,
    output wire        bram_enable,
    output wire [ 7:0] port_id,
    output wire [ 7:0] out_port,
    output wire        write_strobe,
    output wire        k_write_strobe,
    output wire        read_strobe,
    output wire        interrupt_ack,
    output reg  [ 7:0] in_port
);
    reg [17:0] rom [0:4095];
    reg [ 7:0] inputs [0:255];
    reg [ 7:0] cycle_count;
    integer i;

    initial begin
        instruction = 18'h00000;  // a 7-series BRAM's initial output
        in_port = 8'h00;
        cycle_count = 8'h00;
        for (i = 0; i < 4096; i = i + 1) rom[i] = 18'h00000;
        for (i = 0; i < 256; i = i + 1) inputs[i] = 8'h00;
    end

    always @(posedge clk) begin
        if (bram_enable) instruction <= rom[address];
        in_port <= inputs[port_id] ^ cycle_count;
        cycle_count <= cycle_count + 8'd1;
    end

    kcpsm6 #(
        .hwbuild(HWBUILD),
        .interrupt_vector(VECTOR),
        .scratch_pad_memory_size(SPM_SIZE)
    ) cpu (
        .address(address),
        .instruction(instruction),
        .bram_enable(bram_enable),
        .in_port(in_port),
        .out_port(out_port),
        .port_id(port_id),
        .write_strobe(write_strobe),
        .k_write_strobe(k_write_strobe),
        .read_strobe(read_strobe),
        .interrupt(interrupt),
        .interrupt_ack(interrupt_ack),
        .sleep(sleep),
        .reset(reset),
        .clk(clk)
    );
endmodule
