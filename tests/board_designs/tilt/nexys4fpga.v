// nexys4fpga.v: an accelerometer reader (clean-room, written for botsim's tests from spec
// board.md 1, 2 and 7): the team's PicoBlaze runs tilt.psm, which talks to the board's
// ADXL362 over SPI (spi_master.v, 2 MHz): it starts measuring, then at each sample (STATUS
// DATA_READY) reads x and y (8 bits) to the LEDs (x on 15-8, y on 7-0) and x and z (12 bits)
// to the seven-segment display (z on digits 7-4, x on 3-0, hexadecimal).
`timescale 1ns / 1ps
module nexys4fpga (
    input  wire        clk,
    input  wire        btnCpuReset,
    output wire [15:0] led,
    output wire [ 6:0] seg,
    output wire        dp,
    output wire [ 7:0] an,
    output wire        aclSCK,
    output wire        aclMOSI,
    input  wire        aclMISO,
    output reg         aclSS = 1'b1
);
    wire [ 5:0] db_pbtns;
    wire        sysreset = ~db_pbtns[0];
    debounce #(.RESET_POLARITY_LOW(1), .SIMULATE(1)) DB (
        .clk(clk), .pbtn_in({5'd0, btnCpuReset}), .switch_in(16'd0), .pbtn_db(db_pbtns), .swtch_db()
    );

    wire [11:0] address;
    wire [17:0] instruction;
    wire        bram_enable, rdl;
    wire [ 7:0] port_id, out_port;
    reg  [ 7:0] in_port = 8'd0;
    wire        write_strobe, k_write_strobe, read_strobe, interrupt_ack;
    kcpsm6 #(.interrupt_vector(12'h3FF), .scratch_pad_memory_size(64), .hwbuild(8'h00)) TILTCPU (
        .address(address), .instruction(instruction), .bram_enable(bram_enable),
        .port_id(port_id), .write_strobe(write_strobe), .k_write_strobe(k_write_strobe),
        .out_port(out_port), .read_strobe(read_strobe), .in_port(in_port),
        .interrupt(1'b0), .interrupt_ack(interrupt_ack), .sleep(1'b0),
        .reset(sysreset | rdl), .clk(clk)
    );
    tilt PGM (.enable(bram_enable), .address(address), .instruction(instruction), .rdl(rdl), .clk(clk));

    wire [7:0] spi_rx;
    wire spi_busy;
    spi_master SPI (.clk(clk), .start(write_strobe && port_id == 8'h10), .tx(out_port), .rx(spi_rx),
                    .busy(spi_busy), .sck(aclSCK), .mosi(aclMOSI), .miso(aclMISO));

    reg [15:0] leds = 16'd0;
    reg [15:0] x12 = 16'd0, z12 = 16'd0;
    always @(posedge clk) begin
        case (port_id)
            8'h10: in_port <= spi_rx;
            8'h11: in_port <= {7'd0, spi_busy};
            default: in_port <= 8'h00;
        endcase
        if (write_strobe) begin
            case (port_id)
                8'h11: aclSS <= out_port[0];
                8'h02: leds[7:0] <= out_port;
                8'h12: leds[15:8] <= out_port;
                8'h03: x12[7:0] <= out_port;
                8'h04: x12[15:8] <= out_port;
                8'h05: z12[7:0] <= out_port;
                8'h06: z12[15:8] <= out_port;
                default: ;
            endcase
        end
    end
    assign led = leds;

    sevensegment #(.RESET_POLARITY_LOW(0), .SIMULATE(1)) SSB (
        .clk(clk), .reset(sysreset),
        .d7({1'b0, z12[15:12]}), .d6({1'b0, z12[11:8]}), .d5({1'b0, z12[7:4]}), .d4({1'b0, z12[3:0]}),
        .d3({1'b0, x12[15:12]}), .d2({1'b0, x12[11:8]}), .d1({1'b0, x12[7:4]}), .d0({1'b0, x12[3:0]}),
        .dp(8'h00), .seg({dp, seg}), .an(an), .digits_out()
    );
endmodule
