// kcpsm6_iss.v: botsim's KCPSM6 for `botsim board --cpu iss` (not synthesizable).
//
// The same module name, parameters and ports as rtl/kcpsm6.v, with the core behind them
// botsim's cycle-exact instruction-set simulator (kcpsm6/src/iss.rs) instead of RTL: only
// the design around it is left to evaluate, cycle by cycle. The ISS holds the program of the ROM that
// botsim found wired to this instance's `instruction` port; it checks every decoded word
// against that port and reports the first difference (a ROM wired otherwise, or changed at
// run time).
//
// One call per rising edge of `clk`: the inputs as they are before the edge (`in_port` is
// the value an INPUT reads at the end of its strobe cycle) go in; the outputs of the next
// cycle come back, registered here like the RTL core's flops and combinational reads.
//   pins  = instruction | in_port << 18 | interrupt << 26 | sleep << 27 | reset << 28
//   state = address | bram_enable << 12 | out_port << 13 | port_id << 21 |
//           write_strobe << 29 | k_write_strobe << 30 | read_strobe << 31 | interrupt_ack << 32
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
    import "DPI-C" function chandle botsim_iss_new(
        input string path, input int hwbuild_byte, input int vector_address, input int spm_bytes
    );
    import "DPI-C" function longint botsim_iss_state(input chandle cpu);
    import "DPI-C" function longint botsim_iss_tick(input chandle cpu, input longint pins);

    // The model, and its outputs of the current cycle (bits 63:33 zero). The board's
    // fast-forward finds both by these names: it compares the model itself, not its outputs
    // here, and sets them from the model after a skip (src/board/counts.rs).
    chandle botsim_iss_cpu;
    reg [63:0] botsim_iss_q;

    initial begin
        botsim_iss_cpu = botsim_iss_new($sformatf("%m"), {24'd0, hwbuild}, {20'd0, interrupt_vector},
                                        scratch_pad_memory_size);
        botsim_iss_q = botsim_iss_state(botsim_iss_cpu);
    end

`ifndef BOTSIM_DEBUG
    always @(posedge clk)
        botsim_iss_q <= botsim_iss_tick(botsim_iss_cpu, {35'd0, reset, sleep, interrupt, in_port, instruction});
`else
    // Debug signals (botsim board --vcd builds), with the names and the format of
    // rtl/kcpsm6.v's: the text of the word on `instruction`, the status, the active bank's
    // registers, all from the model after each edge.
    import "DPI-C" function void botsim_disasm(input int word, output bit [159:0] text);
    import "DPI-C" function void botsim_iss_debug(input chandle cpu, output bit [127:0] regs, output int flags);
    reg  [1:160] kcpsm6_opcode;
    reg  [127:0] active_registers;
    reg  [31:0]  flags;  // bank, zero, carry, interrupt enable, reset, sleep, interrupt entry
    reg  [63:0]  next_state;
    reg  [127:0] next_registers;
    reg  [31:0]  next_flags;
    initial begin
        active_registers = 128'd0;
        flags = 32'h10;
    end
    always @(instruction) botsim_disasm({14'd0, instruction}, kcpsm6_opcode);
    always @(posedge clk) begin
        next_state = botsim_iss_tick(botsim_iss_cpu, {35'd0, reset, sleep, interrupt, in_port, instruction});
        botsim_iss_debug(botsim_iss_cpu, next_registers, next_flags);
        botsim_iss_q <= next_state;
        active_registers <= next_registers;
        flags <= next_flags;
    end
    wire [1:128] kcpsm6_status = {flags[0] ? "B" : "A", flags[1] ? ", Z" : ",NZ", flags[2] ? ", C" : ",NC",
                                  flags[3] ? ",IE" : ",ID",
                                  flags[4] ? ",Reset" : flags[5] ? ",Sleep" : flags[6] ? ",Intrp" : "      "};
    wire [7:0] sim_s0 = active_registers[7:0],     sim_s1 = active_registers[15:8];
    wire [7:0] sim_s2 = active_registers[23:16],   sim_s3 = active_registers[31:24];
    wire [7:0] sim_s4 = active_registers[39:32],   sim_s5 = active_registers[47:40];
    wire [7:0] sim_s6 = active_registers[55:48],   sim_s7 = active_registers[63:56];
    wire [7:0] sim_s8 = active_registers[71:64],   sim_s9 = active_registers[79:72];
    wire [7:0] sim_sA = active_registers[87:80],   sim_sB = active_registers[95:88];
    wire [7:0] sim_sC = active_registers[103:96],  sim_sD = active_registers[111:104];
    wire [7:0] sim_sE = active_registers[119:112], sim_sF = active_registers[127:120];
`endif

    assign address        = botsim_iss_q[11:0];
    assign bram_enable    = botsim_iss_q[12];
    assign out_port       = botsim_iss_q[20:13];
    assign port_id        = botsim_iss_q[28:21];
    assign write_strobe   = botsim_iss_q[29];
    assign k_write_strobe = botsim_iss_q[30];
    assign read_strobe    = botsim_iss_q[31];
    assign interrupt_ack  = botsim_iss_q[32];
endmodule
