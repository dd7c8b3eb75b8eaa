// devices.v: the Nexys4's peripherals outside the FPGA, as the board wrapper connects them to a
// design's pins (spec board.md §7), written from their datasheets' behaviour, clean-room.
// Not synthesizable (initial values), all on the board's 100 MHz clock, rising edges only.
//
//   botsim_byte_queue     what the host (botsim) has to send, fed a few bytes at a time
//   botsim_uart_source    the USB-UART bridge's line into the FPGA (RsRx): 8N1 at `div`
//                         clocks a bit
//   botsim_ps2_keyboard   a keyboard behind the board's USB host: PS/2 device-to-host frames
//                         at 12.5 kHz, waiting while the host inhibits (holds the clock low)
//   botsim_adxl362        the accelerometer on SPI mode 0: its commands, registers and
//                         samples at the output data rate, from the board's tilt
`timescale 1ns / 1ps

// A queue of up to 64 bytes. Each change of `push` appends the first `push_n` (1-8) bytes of
// `push_bytes` (the first in bits 7:0) at the next clock edge; `pending` is high until then
// (the harness pushes again only after it falls, and only as much as `room` allows). `take`
// drops the head.
module botsim_byte_queue (
    input  wire        clk,
    input  wire        push,
    input  wire [ 3:0] push_n,
    input  wire [63:0] push_bytes,
    input  wire        take,
    output wire [ 7:0] head,
    output wire        ready,
    output wire [ 6:0] room,
    output wire        pending
);
    reg [7:0] q[0:63];
    reg [6:0] wr = 7'd0, rd = 7'd0;
    reg pushed = 1'b0;
    wire [6:0] used = wr - rd;
    assign room = 7'd64 - used;
    assign ready = used != 7'd0;
    assign head = q[rd[5:0]];
    assign pending = push != pushed;
    integer i;
    always @(posedge clk) begin
        if (pending) begin
            pushed <= push;
            for (i = 0; i < 8; i = i + 1)
                if (i < push_n) q[wr[5:0]+i[5:0]] <= push_bytes[8*i+:8];
            wr <= wr + {3'd0, push_n};
        end
        if (take && ready) rd <= rd + 7'd1;
    end
endmodule

// The USB-UART bridge's transmitter towards the FPGA: each queued byte as a start bit (0),
// eight data bits least significant first and a stop bit (1), each `div` clocks long, back to
// back; the line idles high.
module botsim_uart_source (
    input  wire        clk,
    input  wire [31:0] div,
    input  wire        push,
    input  wire [ 3:0] push_n,
    input  wire [63:0] push_bytes,
    output reg         line = 1'b1,
    output wire [ 6:0] room,
    output wire        pending
);
    reg        busy = 1'b0;
    reg [ 3:0] bitn = 4'd0;  // 0 start, 1-8 data, 9 stop
    reg [31:0] left = 32'd0;  // clocks left of the bit after this one
    reg [ 7:0] data = 8'd0;
    wire [7:0] head;
    wire ready;
    wire start = !busy && ready;
    botsim_byte_queue queue (
        .clk(clk), .push(push), .push_n(push_n), .push_bytes(push_bytes), .take(start),
        .head(head), .ready(ready), .room(room), .pending(pending)
    );
    always @(posedge clk) begin
        if (start) begin
            busy <= 1'b1;
            data <= head;
            bitn <= 4'd0;
            line <= 1'b0;
            left <= div - 32'd1;
        end else if (busy) begin
            if (left != 32'd0) begin
                left <= left - 32'd1;
            end else if (bitn == 4'd9) begin
                busy <= 1'b0;
            end else begin
                bitn <= bitn + 4'd1;
                line <= bitn == 4'd8 ? 1'b1 : data[bitn[2:0]];
                left <= div - 32'd1;
            end
        end
    end
endmodule

// A PS/2 keyboard sending the queued bytes (scan codes) to the host, one device-to-host frame
// each: start (0), eight data bits least significant first, odd parity, stop (1). The device
// drives both lines open collector (`*_low` pulls a line low); the lines as they are on the
// board, the host's pulls and the pull-ups included, come back in `clk_line` and `data_line`.
// A bit is 80 us (a 12.5 kHz clock): the data changes, 20 us later the clock falls (the host
// reads the bit), 40 us later it rises, 20 us to the next bit. A frame starts only after both
// lines have been high for 50 us; a host that holds the clock low while the device releases it
// (inhibit) aborts the frame, and the byte is sent again when the lines are free.
module botsim_ps2_keyboard (
    input  wire        clk,
    input  wire        push,
    input  wire [ 3:0] push_n,
    input  wire [63:0] push_bytes,
    input  wire        clk_line,
    input  wire        data_line,
    output reg         clk_low = 1'b0,
    output reg         data_low = 1'b0,
    output wire [ 6:0] room,
    output wire        pending
);
    localparam [12:0] BIT = 13'd8000, FALL = 13'd2000, RISE = 13'd6000;  // clocks of 10 ns
    localparam [12:0] FREE = 13'd5000;  // 50 us of free lines before a frame
    reg        busy = 1'b0;
    reg [ 3:0] bitn = 4'd0;  // 0 start, 1-8 data, 9 parity, 10 stop
    reg [12:0] phase = 13'd0;  // clocks into the bit
    reg [12:0] free = 13'd0;  // clocks both lines have been high (up to FREE)
    reg [10:0] frame = 11'd0;  // the frame's bits, the next one out in bit 0
    wire [7:0] head;
    wire ready;
    wire done = busy && bitn == 4'd10 && phase == BIT - 13'd1;
    botsim_byte_queue queue (
        .clk(clk), .push(push), .push_n(push_n), .push_bytes(push_bytes), .take(done),
        .head(head), .ready(ready), .room(room), .pending(pending)
    );
    wire inhibited = !clk_low && !clk_line;  // released by the device, low on the line
    always @(posedge clk) begin
        free <= (clk_line && data_line) ? (free == FREE ? FREE : free + 13'd1) : 13'd0;
        if (!busy) begin
            clk_low <= 1'b0;
            data_low <= 1'b0;
            if (ready && free == FREE) begin
                busy <= 1'b1;
                bitn <= 4'd0;
                phase <= 13'd0;
                frame <= {1'b1, ~^head, head, 1'b0};
                data_low <= 1'b1;  // the start bit
            end
        end else if (inhibited) begin
            busy <= 1'b0;  // the host inhibits: send the byte again later
            clk_low <= 1'b0;
            data_low <= 1'b0;
        end else if (phase == BIT - 13'd1) begin
            phase <= 13'd0;
            if (bitn == 4'd10) begin
                busy <= 1'b0;
                data_low <= 1'b0;
            end else begin
                bitn <= bitn + 4'd1;
                data_low <= !frame[1];
                frame <= frame >> 1;
            end
        end else begin
            phase <= phase + 13'd1;
            if (phase == FALL - 13'd1) clk_low <= 1'b1;
            if (phase == RISE - 13'd1) clk_low <= 1'b0;
        end
    end
endmodule

// The ADXL362 accelerometer as a design sees it on SPI mode 0 (the clock idles low; the device
// samples `mosi` at the clock's rising edges and changes `miso` at its falling edges, most
// significant bit first; `cs_n` low frames a transaction). The first byte is the command:
// 0A write registers, 0B read registers (then an address byte, then data bytes, the address
// incrementing), 0D read the FIFO (zeros here). Registers: 00-03 the IDs (AD 1D F2 02);
// 08-0A the 8 most significant bits of x, y, z; 0B STATUS (bit 0 DATA_READY, cleared by a read
// of the data); 0E-13 x, y, z as 12-bit two's complement, low byte first, the high byte
// sign-extended; 1F SOFT_RESET (52 resets); 20-2E the configuration, of which FILTER_CTL (2C:
// range in bits 7:6, output data rate in bits 2:0), POWER_CTL (2D: bits 1:0 = 10 measures)
// and INTMAP1/2 (2A/2B: bit 0 maps DATA_READY, bit 7 makes the pin active low) act. While
// measuring, the data registers take the board's tilt (`x_mg`, `y_mg`, `z_mg`, in mg) at the
// output data rate (12.5 Hz << ODR, 400 Hz at most; the first sample one period after the
// start), scaled by the range (1, 2 or 4 mg a
// bit) and limited to 12 bits; before the first sample they read 0. The temperature reads 0.
// The clock and select are sampled on the board's clock: a design's SPI clock up to 25 MHz.
module botsim_adxl362 (
    input  wire        clk,
    input  wire        sck,
    input  wire        mosi,
    input  wire        cs_n,
    output reg         miso = 1'b0,
    output wire        int1,
    output wire        int2,
    input  wire [15:0] x_mg,
    input  wire [15:0] y_mg,
    input  wire [15:0] z_mg
);
    reg [7:0] cfg[0:15];  // 20-2F
    reg [11:0] x = 12'd0, y = 12'd0, z = 12'd0;
    reg ready = 1'b0;  // STATUS bit 0
    // Clocks since the last sample (or since measuring began): a sample is due at the end
    // of the output data rate's period, each period's end a comparison of its own, so that
    // between samples the counter only counts (the fast-forward skips from one to the next).
    reg [22:0] since = 23'd0;
    reg sck_q = 1'b0;
    reg [6:0] shift_in = 7'd0;
    reg [7:0] shift_out = 8'd0, command = 8'd0, addr = 8'd0;
    reg [2:0] bitn = 3'd0;  // rising clock edges into the byte
    reg [1:0] phase = 2'd0;  // the byte: 0 the command, 1 the address, 2 data
    integer i;
    initial begin
        for (i = 0; i < 16; i = i + 1) cfg[i] = 8'd0;
        cfg[4'hC] = 8'h13;  // FILTER_CTL: +-2 g, 100 Hz
    end

    wire measuring = cfg[4'hD][1:0] == 2'b10;
    wire [2:0] odr = cfg[4'hC][2:0] > 3'd5 ? 3'd5 : cfg[4'hC][2:0];
    wire [5:0] ends = {since == 23'd249999, since == 23'd499999, since == 23'd999999,
                       since == 23'd1999999, since == 23'd3999999, since == 23'd7999999};
    wire due = ends[odr];  // 12.5 Hz << odr
    wire [1:0] range = cfg[4'hC][7:6];
    // One axis in the range's units, limited to 12 bits.
    function [11:0] scaled(input [15:0] mg, input [1:0] r);
        reg signed [15:0] v;
        begin
            v = $signed(mg) >>> (r == 2'd0 ? 0 : r == 2'd1 ? 1 : 2);
            scaled = v > 16'sd2047 ? 12'h7FF : v < -16'sd2048 ? 12'h800 : v[11:0];
        end
    endfunction
    function [7:0] register(input [7:0] a);
        case (a)
            8'h00: register = 8'hAD;
            8'h01: register = 8'h1D;
            8'h02: register = 8'hF2;
            8'h03: register = 8'h02;
            8'h08: register = x[11:4];
            8'h09: register = y[11:4];
            8'h0A: register = z[11:4];
            8'h0B: register = {7'd0, ready};
            8'h0E: register = x[7:0];
            8'h0F: register = {{4{x[11]}}, x[11:8]};
            8'h10: register = y[7:0];
            8'h11: register = {{4{y[11]}}, y[11:8]};
            8'h12: register = z[7:0];
            8'h13: register = {{4{z[11]}}, z[11:8]};
            default: register = (a >= 8'h20 && a <= 8'h2F) ? cfg[a[3:0]] : 8'h00;
        endcase
    endfunction
    wire [7:0] reg_out = register(addr);
    wire data_register = addr == 8'h08 || addr == 8'h09 || addr == 8'h0A || (addr >= 8'h0E && addr <= 8'h13);
    assign int1 = (cfg[4'hA][0] & ready) ^ cfg[4'hA][7];
    assign int2 = (cfg[4'hB][0] & ready) ^ cfg[4'hB][7];

    wire rising = sck && !sck_q && !cs_n;
    wire falling = !sck && sck_q && !cs_n;
    wire [7:0] byte_in = {shift_in[6:0], mosi};
    always @(posedge clk) begin
        sck_q <= sck;
        // Samples at the output data rate while measuring.
        if (!measuring) begin
            since <= 23'd0;
        end else if (due) begin
            since <= 23'd0;
            x <= scaled(x_mg, range);
            y <= scaled(y_mg, range);
            z <= scaled(z_mg, range);
            ready <= 1'b1;
        end else begin
            since <= since + 23'd1;
        end
        if (cs_n) begin
            bitn <= 3'd0;
            phase <= 2'd0;
            miso <= 1'b0;
        end else if (rising) begin
            shift_in <= byte_in[6:0];
            bitn <= bitn + 3'd1;
            if (bitn == 3'd7) begin
                if (phase != 2'd2) phase <= phase + 2'd1;
                if (phase == 2'd0) begin
                    command <= byte_in;
                end else if (phase == 2'd1) begin
                    addr <= byte_in;
                end else begin
                    if (command == 8'h0A) begin
                        if (addr == 8'h1F && byte_in == 8'h52) begin
                            for (i = 0; i < 16; i = i + 1) cfg[i] <= 8'd0;
                            cfg[4'hC] <= 8'h13;
                            {x, y, z} <= 36'd0;
                            ready <= 1'b0;
                        end else if (addr >= 8'h20 && addr <= 8'h2E) begin
                            cfg[addr[3:0]] <= byte_in;
                        end
                    end
                    if (command == 8'h0B && data_register) ready <= 1'b0;
                    addr <= addr + 8'd1;
                end
            end
        end else if (falling && command == 8'h0B && phase == 2'd2) begin
            if (bitn == 3'd0) begin
                miso <= reg_out[7];
                shift_out <= {reg_out[6:0], 1'b0};
            end else begin
                miso <= shift_out[7];
                shift_out <= {shift_out[6:0], 1'b0};
            end
        end
    end
endmodule
