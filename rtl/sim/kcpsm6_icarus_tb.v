// kcpsm6_icarus_tb.v: the CPU test harness under Icarus Verilog, for the spec-rule tests that
// must hold in a four-state simulator too (tests/common/icarus.rs). Plusargs: +rom=FILE (the
// program, $readmemh), +pins=FILE (one hex digit per cycle: bit 0 reset, 1 sleep, 2
// interrupt), +cycles=N. Each cycle drives the pins, lets the design settle, prints the
// ports ("x" where a bit is unknown), then gives the clock its rising edge: the cycle as
// botsim's Verilator harness and the ISS count it.
`timescale 1ns / 1ps
module kcpsm6_icarus_tb;
    reg clk = 1'b0, reset = 1'b0, sleep = 1'b0, interrupt = 1'b0;
    wire [11:0] address;
    wire [17:0] instruction;
    wire [7:0] port_id, out_port, in_port;
    wire bram_enable, write_strobe, k_write_strobe, read_strobe, interrupt_ack;
    reg [3:0] pins [0:65535];
    reg [1023:0] file;
    integer cycles, c;

    kcpsm6_harness dut (
        .clk(clk), .reset(reset), .sleep(sleep), .interrupt(interrupt), .address(address),
        .instruction(instruction), .bram_enable(bram_enable), .port_id(port_id), .out_port(out_port),
        .write_strobe(write_strobe), .k_write_strobe(k_write_strobe), .read_strobe(read_strobe),
        .interrupt_ack(interrupt_ack), .in_port(in_port)
    );

    initial begin
        if ($value$plusargs("rom=%s", file)) $readmemh(file, dut.rom);
        if ($value$plusargs("pins=%s", file)) $readmemh(file, pins);
        if (!$value$plusargs("cycles=%d", cycles)) cycles = 0;
        for (c = 0; c < cycles; c = c + 1) begin
            {interrupt, sleep, reset} = pins[c][2:0];
            #1;
            $display("%h %h %b %h %h %b %b %b %b", address, instruction, bram_enable, port_id, out_port,
                     read_strobe, write_strobe, k_write_strobe, interrupt_ack);
            #4 clk = 1'b1;
            #5 clk = 1'b0;
        end
        $finish;
    end
endmodule
