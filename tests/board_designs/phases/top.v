// top.v: a KCPSM6 in a wait loop of six cycles beside a display refresh counter of 2^16
// clocks (test design for botsim board's fast-forward): the board repeats itself every
// 3 x 2^16 clocks, and the CPU's phase at a fraction of that period is not its phase at the
// start, so a fast-forward that put the board back at such a phase must put the CPU back too.
// Each sample of the bot interrupts the CPU, which counts them on the LEDs.
`timescale 1ns / 1ps
module top (
    input  wire        clk,
    input  wire        btnCpuReset,
    output wire [ 7:0] an,
    output wire [ 6:0] seg,
    output wire [15:0] led
);
    wire [11:0] address;
    wire [17:0] instruction;
    wire [ 7:0] port_id, out_port;
    wire        bram_enable, write_strobe, k_write_strobe, read_strobe, interrupt_ack;
    wire        upd_sysregs;
    reg         interrupt = 1'b0;
    reg  [ 7:0] count = 8'h00;
    reg  [15:0] refresh = 16'd0;

    kcpsm6 cpu (
        .address(address), .instruction(instruction), .bram_enable(bram_enable),
        .in_port(8'h00), .out_port(out_port), .port_id(port_id),
        .write_strobe(write_strobe), .k_write_strobe(k_write_strobe), .read_strobe(read_strobe),
        .interrupt(interrupt), .interrupt_ack(interrupt_ack), .sleep(1'b0), .reset(~btnCpuReset),
        .clk(clk)
    );
    phases rom (.address(address), .instruction(instruction), .enable(bram_enable), .clk(clk));

    always @(posedge clk) begin
        if (write_strobe) count <= out_port;
        if (interrupt_ack) interrupt <= 1'b0;
        else if (upd_sysregs) interrupt <= 1'b1;
        refresh <= refresh + 16'd1;
    end
    // Eight digits, each lit for 2^13 clocks in turn, showing the count's low bits.
    assign an  = ~(8'h01 << refresh[15:13]);
    assign seg = {count[2:0], refresh[15:13], 1'b0};
    assign led = {8'h00, count};

    bot robot (.MotCtl_in(8'h33), .LocX_reg(), .LocY_reg(), .Sensors_reg(), .BotInfo_reg(),
               .LMDist_reg(), .RMDist_reg(), .vid_row(10'd0), .vid_col(10'd0), .vid_pixel_out(),
               .clk(clk), .reset(~btnCpuReset), .upd_sysregs(upd_sysregs));
endmodule

// The program ROM's interface (botsim puts phases.psm in it: `--program phases.psm`).
module phases (
    input  wire [11:0] address,
    output reg  [17:0] instruction,
    input  wire        enable,
    input  wire        clk
);
    always @(posedge clk) if (enable) instruction <= 18'h00000;
endmodule
