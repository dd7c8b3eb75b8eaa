// kcpsm6_probe.v: botsim's RTL KCPSM6 with a probe on its ports, for `botsim board --cpu
// lockstep` (not synthesizable). The RTL core is rtl/kcpsm6.v renamed `kcpsm6_rtl`; this
// `kcpsm6` wraps it and hands the host every cycle's pins and outputs at the rising edge
// that ends the cycle, packed as kcpsm6_iss.v packs them, so the host compares them with
// the instruction-set simulator's cycle for cycle.
`timescale 1ns / 1ps
module kcpsm6 #(
    parameter [7:0] hwbuild = 8'h00,
    parameter [11:0] interrupt_vector = 12'h3FF,
    parameter integer scratch_pad_memory_size = 64
) (
    output wire [11:0] address,
    input  wire [17:0] instruction,
    output wire        bram_enable,
    input  wire [ 7:0] in_port,
    output wire [ 7:0] out_port,
    output wire [ 7:0] port_id,
    output wire        write_strobe,
    output wire        k_write_strobe,
    output wire        read_strobe,
    input  wire        interrupt,
    output wire        interrupt_ack,
    input  wire        sleep,
    input  wire        reset,
    input  wire        clk
);
    import "DPI-C" function chandle botsim_probe_new(input string path);
    import "DPI-C" function void botsim_probe(input chandle probe, input longint pins, input longint state);

    kcpsm6_rtl #(
        .hwbuild(hwbuild),
        .interrupt_vector(interrupt_vector),
        .scratch_pad_memory_size(scratch_pad_memory_size)
    ) core (
        .address(address), .instruction(instruction), .bram_enable(bram_enable),
        .in_port(in_port), .out_port(out_port), .port_id(port_id),
        .write_strobe(write_strobe), .k_write_strobe(k_write_strobe), .read_strobe(read_strobe),
        .interrupt(interrupt), .interrupt_ack(interrupt_ack), .sleep(sleep), .reset(reset),
        .clk(clk)
    );

    chandle probe;
    initial probe = botsim_probe_new($sformatf("%m"));

    always @(posedge clk)
        botsim_probe(probe, {35'd0, reset, sleep, interrupt, in_port, instruction},
                     {31'd0, interrupt_ack, read_strobe, k_write_strobe, write_strobe, port_id,
                      out_port, bram_enable, address});
endmodule
