// nexys4fpga.v: a tone player (clean-room, written for botsim's tests from spec board.md 1,
// 2 and 7). The team's PicoBlaze runs tones.psm: switches 2-0 choose a note (C4 to C5),
// switch 15 turns the amplifier on (ampSD); the program writes the note's half period in
// clocks to the tone generator, whose square wave is played through an 8-bit PWM (390 kHz,
// half duty while the wave is high) on ampPWM, driven low or left floating as the board's
// open-drain audio input wants. The note's number is on the display, the switches on the LEDs.
`timescale 1ns / 1ps
module nexys4fpga (
    input  wire        clk,
    input  wire        btnCpuReset,
    input  wire [15:0] sw,
    output wire [15:0] led,
    output wire [ 6:0] seg,
    output wire        dp,
    output wire [ 7:0] an,
    output wire        ampPWM,
    output reg         ampSD = 1'b0
);
    wire [ 5:0] db_pbtns;
    wire [15:0] db_sw;
    wire        sysreset = ~db_pbtns[0];
    debounce #(.RESET_POLARITY_LOW(1), .SIMULATE(1)) DB (
        .clk(clk), .pbtn_in({5'd0, btnCpuReset}), .switch_in(sw), .pbtn_db(db_pbtns), .swtch_db(db_sw)
    );

    wire [11:0] address;
    wire [17:0] instruction;
    wire        bram_enable, rdl;
    wire [ 7:0] port_id, out_port;
    reg  [ 7:0] in_port = 8'd0;
    wire        write_strobe, k_write_strobe, read_strobe, interrupt_ack;
    kcpsm6 #(.interrupt_vector(12'h3FF), .scratch_pad_memory_size(64), .hwbuild(8'h00)) TONECPU (
        .address(address), .instruction(instruction), .bram_enable(bram_enable),
        .port_id(port_id), .write_strobe(write_strobe), .k_write_strobe(k_write_strobe),
        .out_port(out_port), .read_strobe(read_strobe), .in_port(in_port),
        .interrupt(1'b0), .interrupt_ack(interrupt_ack), .sleep(1'b0),
        .reset(sysreset | rdl), .clk(clk)
    );
    tones PGM (.enable(bram_enable), .address(address), .instruction(instruction), .rdl(rdl), .clk(clk));

    reg [23:0] half = 24'd0;  // the note's half period in clocks (0: silence)
    reg [ 4:0] note = 5'h17;  // blank
    always @(posedge clk) begin
        case (port_id)
            8'h00: in_port <= db_sw[7:0];
            8'h01: in_port <= db_sw[15:8];
            default: in_port <= 8'h00;
        endcase
        if (write_strobe) begin
            case (port_id)
                8'h20: half[7:0] <= out_port;
                8'h21: half[15:8] <= out_port;
                8'h22: half[23:16] <= out_port;
                8'h23: ampSD <= out_port[0];
                8'h24: note <= out_port[4:0];
                default: ;
            endcase
        end
    end
    assign led = db_sw;

    // The tone: a square wave of the note's period, through the PWM.
    reg [23:0] count = 24'd0;
    reg wave = 1'b0;
    reg [7:0] pwm = 8'd0;
    always @(posedge clk) begin
        pwm <= pwm + 8'd1;
        if (half == 24'd0) begin
            count <= 24'd0;
            wave <= 1'b0;
        end else if (count + 24'd1 >= half) begin
            count <= 24'd0;
            wave <= !wave;
        end else begin
            count <= count + 24'd1;
        end
    end
    assign ampPWM = (wave && pwm < 8'd128) ? 1'bz : 1'b0;

    sevensegment #(.RESET_POLARITY_LOW(0), .SIMULATE(1)) SSB (
        .clk(clk), .reset(sysreset),
        .d7(5'h17), .d6(5'h17), .d5(5'h17), .d4(5'h17), .d3(5'h17), .d2(5'h17), .d1(5'h17), .d0(note),
        .dp(8'h00), .seg({dp, seg}), .an(an), .digits_out()
    );
endmodule
