// kcpsm6.v: a clean-room, cycle-exact KCPSM6 (PicoBlaze-6) core.
//
// Behavioural and synthesizable Verilog-2005 with the module name, port list and parameters of
// Xilinx's kcpsm6, so it drops into an existing design in place of the netlist. Written from
// the botsim specification (spec/kcpsm6.md); no Xilinx code. The ISS in kcpsm6/src/iss.rs
// follows the same flops, one for one, and runs in lock-step with this core in the tests.
//
// Sequencing (spec 2.2): every instruction takes a D cycle and a second cycle, normally F.
//   D   the word is on `instruction`; operands are read and the ALU result, carry and zero are
//       registered (2.8); PC, call-stack depth, IE and bank update at its end; the stack RAM
//       is written; the second-cycle action flops are loaded.
//   F   bram_enable: the ROM loads the next word at its end; the register, flag and
//       scratch-pad writes and the port strobes of the instruction happen here (or in the
//       first idle cycle when sleep stops the fetch, or during a reset: 2.4, 2.5).
//
//   t_state  00 idle (reset sequence, sleep)   10 F   01 D
//   00 -> F unless sleeping; F -> D; D -> F unless sleeping, else 00; internal reset -> 00.
//
// Reset (2.4) goes through two flops, `run` and `internal_reset`. A stack overflow or
// underflow (2.5) is a wrapping depth counter reaching 31, seen in the F after the offending
// D, and acts like the reset pin sampled high at the end of that F.
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

    // ---- parameters --------------------------------------------------------------------------
    localparam integer SPM_BITS = scratch_pad_memory_size == 256 ? 8 :
                                  scratch_pad_memory_size == 128 ? 7 : 6;

    generate
        if (scratch_pad_memory_size != 64 && scratch_pad_memory_size != 128 &&
            scratch_pad_memory_size != 256) begin : bad_parameter
            // Elaboration fails here: scratch_pad_memory_size must be 64, 128 or 256.
            kcpsm6_scratch_pad_memory_size_must_be_64_128_or_256 invalid_parameter ();
        end
    endgenerate

    // ---- state -------------------------------------------------------------------------------
    localparam [1:0] T_IDLE = 2'b00, T_FETCH = 2'b10, T_DECODE = 2'b01;

    reg  [ 1:0] t_state = T_IDLE;
    reg         run = 1'b0;               // cleared by reset and by a stack error
    reg         internal_reset = 1'b0;    // clears PC, flags, IE, bank and depth at its end
    reg         sleep_q = 1'b0;           // registered pins
    reg         interrupt_q = 1'b0;
    reg         active_interrupt = 1'b0;  // recognised in the last F: this D is an entry
    reg         interrupt_ack_q = 1'b0;

    reg  [11:0] pc = 12'h000;
    reg         carry = 1'b0;
    reg         zero = 1'b0;
    reg         interrupt_enable = 1'b0;
    reg         bank = 1'b0;              // active register bank (0 = A)
    reg         xb = 1'b0;                // bank of the sX read port and the write port (2.8)
    reg  [ 4:0] depth = 5'd0;             // call-stack depth, wraps modulo 32 (2.5)

    reg  [ 7:0] registers [0:31];         // {bank, register}
    reg  [ 7:0] scratch_pad [0:scratch_pad_memory_size-1];
    reg  [14:0] stack_ram [0:31];         // {bank, zero, carry, pc}

    // Second-cycle actions and the ALU result, loaded at the end of D (2.2, 2.8).
    reg         register_write_q = 1'b0;
    reg         flag_write_q = 1'b0;
    reg         scratch_pad_write_q = 1'b0;
    reg         read_strobe_q = 1'b0;
    reg         write_strobe_q = 1'b0;
    reg         k_write_strobe_q = 1'b0;
    reg  [ 7:0] result_q = 8'h00;
    reg         carry_q = 1'b0;
    reg         zero_q = 1'b0;

    integer i;
    initial begin
        // The device configures its distributed RAMs to zero; reset never clears them.
        for (i = 0; i < 32; i = i + 1) registers[i] = 8'h00;
        for (i = 0; i < 32; i = i + 1) stack_ram[i] = 15'h0000;
        for (i = 0; i < scratch_pad_memory_size; i = i + 1) scratch_pad[i] = 8'h00;
    end

    wire in_decode = t_state == T_DECODE;
    wire in_fetch  = t_state == T_FETCH;

    // ---- instruction fields --------------------------------------------------------------------
    wire [ 5:0] opcode  = instruction[17:12];
    wire [ 3:0] sx_addr = instruction[11:8];
    wire [ 3:0] sy_addr = instruction[7:4];
    wire [ 7:0] kk      = instruction[7:0];
    wire [11:0] aaa     = instruction[11:0];

    // ---- register file: two kinds of read port (2.8) -------------------------------------------
    // sY follows the live bank flop; sX (and the write port) the registered `xb`, so after a
    // bank switch out_port lags port_id by a cycle, and after STAR's D xb is the other bank.
    wire [ 7:0] sx = registers[{xb, sx_addr}];
    wire [ 7:0] sy = registers[{bank, sy_addr}];
    wire [ 7:0] operand = opcode[0] ? kk : sy;  // odd opcodes take the constant
    wire [SPM_BITS-1:0] spm_addr = operand[SPM_BITS-1:0];

    // ---- decode: register/flag/scratch-pad/port class (spec 1.7) -------------------------------
    wire op_load        = opcode[5:1] == 5'b00000;  // 00-01
    wire op_logic       = opcode[5:3] == 3'b000 && opcode[2:1] != 2'b00;  // 02-07
    wire op_input       = opcode[5:1] == 5'b00100;  // 08-09
    wire op_fetch       = opcode[5:1] == 5'b00101;  // 0A-0B
    wire op_test        = opcode[5:2] == 4'b0011;   // 0C-0F
    wire op_add         = opcode[5:2] == 4'b0100;   // 10-13
    wire op_shift       = opcode[5:1] == 5'b01010;  // 14-15 (and HWBUILD)
    wire op_star        = opcode[5:1] == 5'b01011;  // 16-17
    wire op_sub         = opcode[5:2] == 4'b0110;   // 18-1B
    wire op_compare     = opcode[5:2] == 4'b0111;   // 1C-1F
    wire op_load_return = opcode == 6'h21;
    wire op_returni     = opcode == 6'h29;
    wire op_outputk     = opcode[5:1] == 5'b10101;  // 2A-2B
    wire op_output      = opcode[5:1] == 5'b10110;  // 2C-2D
    wire op_store       = opcode[5:1] == 5'b10111;  // 2E-2F
    wire with_carry     = opcode[1];                // the CY forms within ADD/SUB/COMPARE/TEST

    wire writes_register = op_load | op_logic | op_input | op_fetch | op_add | op_shift |
                           op_star | op_sub | op_load_return;
    wire writes_flags    = op_logic | op_test | op_add | op_shift | op_sub | op_compare |
                           op_returni;  // RETURNI: the flags saved on the stack

    // ---- decode: control flow (spec 1.2, bit 17 = 1) -------------------------------------------
    wire       conditional = opcode[5] & opcode[4];
    wire [1:0] condition   = opcode[3:2];           // Z, NZ, C, NC
    wire [1:0] flow_kind   = opcode[1:0];           // CALL, RETURN, JUMP, none
    wire       condition_true = condition == 2'd0 ? zero :
                                condition == 2'd1 ? ~zero :
                                condition == 2'd2 ? carry : ~carry;
    wire taken = conditional & condition_true;
    wire op_call_at  = opcode == 6'h24;
    wire op_jump_at  = opcode == 6'h26;
    wire do_call     = opcode == 6'h20 || op_call_at || (taken && flow_kind == 2'b00);
    wire do_return   = opcode == 6'h25 || op_load_return || (taken && flow_kind == 2'b01);
    wire do_jump     = opcode == 6'h22 || op_jump_at || (taken && flow_kind == 2'b10);
    wire op_set_ie   = opcode == 6'h28;
    wire op_regbank  = opcode == 6'h37;

    wire [11:0] target = (op_call_at | op_jump_at) ? {sx[3:0], sy} : aaa;

    // ---- call stack (spec 2.5) -----------------------------------------------------------------
    // The RAM is written in every D at index `depth`; a pop reads depth - 1. A pre-empted
    // instruction does not pop; the entry D pushes.
    wire        stack_push  = active_interrupt | do_call;
    wire        stack_pop   = ~active_interrupt & (do_return | op_returni);
    // The pop index wraps modulo 32 (0 - 1 = 31: the entry below the bottom, 000 at
    // configuration, 2.8). Kept in a 5-bit wire: a simulator may take `depth - 1` inside the
    // brackets at a wider width, and -1 is then no entry at all (Icarus reads x).
    wire [ 4:0] stack_below = depth - 5'd1;
    wire [14:0] stack_top   = stack_ram[stack_below];
    // Overflow (30 + 1) and underflow (0 - 1) both leave 31; checked in F only.
    wire        stack_error = in_fetch & (depth == 5'd31);

    wire [11:0] next_pc = active_interrupt ? interrupt_vector :
                          (do_call | do_jump) ? target :
                          do_return ? stack_top[11:0] + 12'd1 :
                          op_returni ? stack_top[11:0] : pc + 12'd1;

    // ---- ALU, evaluated in D (2.8: the second cycle writes what D computed) --------------------
    wire       carry_in  = with_carry & carry;
    wire [8:0] sum       = {1'b0, sx} + {1'b0, operand} + {8'd0, carry_in};
    wire [8:0] diff      = {1'b0, sx} - {1'b0, operand} - {8'd0, carry_in};  // [8] = borrow
    wire [7:0] logic_result = opcode[2:1] == 2'b01 ? (sx & operand) :
                              opcode[2:1] == 2'b10 ? (sx | operand) : (sx ^ operand);
    wire [7:0] test_result  = sx & operand;

    // Shift sub-code: [7] HWBUILD, [3] right, [2:1] bit shifted in (C, sX[7], sX[0], [0]).
    wire       hwbuild_op  = kk[7];
    wire       shift_right = kk[3];
    wire       shift_in    = kk[2:1] == 2'b00 ? carry :
                             kk[2:1] == 2'b01 ? sx[7] :
                             kk[2:1] == 2'b10 ? sx[0] : kk[0];
    wire [7:0] shift_result = hwbuild_op ? hwbuild :
                              shift_right ? {shift_in, sx[7:1]} : {sx[6:0], shift_in};
    wire       shift_carry  = hwbuild_op | (shift_right ? sx[0] : sx[7]);

    wire [7:0] alu_result  = op_logic  ? logic_result :
                             op_add    ? sum[7:0] :
                             op_sub    ? diff[7:0] :
                             op_shift  ? shift_result :
                             op_fetch  ? scratch_pad[spm_addr] :
                             op_load_return ? kk : operand;  // LOAD, STAR
    wire [7:0] flag_result = op_logic ? logic_result : op_test ? test_result :
                             op_add ? sum[7:0] : op_shift ? shift_result : diff[7:0];
    wire       alu_carry   = op_returni ? stack_top[12] :
                             op_logic ? 1'b0 :
                             op_test  ? (^test_result) ^ carry_in :
                             op_add   ? sum[8] :
                             op_shift ? shift_carry : diff[8];
    wire       z_chain     = with_carry & (op_test | op_add | op_sub | op_compare);
    wire       alu_zero    = op_returni ? stack_top[13] :
                             (flag_result == 8'd0) & (~z_chain | zero);

    // ---- outputs -------------------------------------------------------------------------------
    assign address        = pc;
    assign bram_enable    = in_fetch;
    assign out_port       = instruction[13] ? instruction[11:4] : sx;
    assign port_id        = instruction[12] ? instruction[7:0] : sy;
    assign read_strobe    = read_strobe_q;
    assign write_strobe   = write_strobe_q;
    assign k_write_strobe = k_write_strobe_q;
    assign interrupt_ack  = interrupt_ack_q;

    // ---- sequencing ----------------------------------------------------------------------------
    always @(posedge clk) begin
        sleep_q        <= sleep;
        interrupt_q    <= interrupt;
        run            <= ~reset & (run | internal_reset) & ~stack_error;
        internal_reset <= reset | ~run | stack_error;
        xb             <= in_fetch ? bank : bank ^ op_star;

        if (internal_reset)
            t_state <= T_IDLE;
        else case (t_state)
            T_FETCH: t_state <= T_DECODE;
            default: t_state <= sleep_q ? T_IDLE : T_FETCH;
        endcase
    end

    // Interrupt recognition (2.6): one flop loaded every cycle and never reset, so a request
    // seen in an F whose D starts a reset still acknowledges two cycles later.
    always @(posedge clk) begin
        active_interrupt <= in_fetch & interrupt_enable & interrupt_q;
        interrupt_ack_q  <= active_interrupt;
    end

    // D: stack RAM, the registered ALU result and the second-cycle action flops. Only an
    // accepted interrupt cancels the actions; a reset does not (2.4).
    always @(posedge clk) begin
        if (in_decode) begin
            stack_ram[depth] <= {bank, zero, carry, pc};  // written in every D
            result_q <= alu_result;
            carry_q  <= alu_carry;
            zero_q   <= alu_zero;
        end
        register_write_q    <= in_decode & ~active_interrupt & writes_register;
        flag_write_q        <= in_decode & ~active_interrupt & writes_flags;
        scratch_pad_write_q <= in_decode & ~active_interrupt & op_store;
        read_strobe_q       <= in_decode & ~active_interrupt & op_input;
        write_strobe_q      <= in_decode & ~active_interrupt & op_output;
        k_write_strobe_q    <= in_decode & ~active_interrupt & op_outputk;
    end

    // End of D: PC, depth, IE and bank; all cleared by the internal reset.
    always @(posedge clk) begin
        if (internal_reset) begin
            pc <= 12'h000;
            depth <= 5'd0;
            interrupt_enable <= 1'b0;
            bank <= 1'b0;
        end else if (in_decode) begin
            pc <= next_pc;
            depth <= depth + {4'd0, stack_push} - {4'd0, stack_pop};
            if (active_interrupt)
                interrupt_enable <= 1'b0;
            else if (op_set_ie | op_returni)
                interrupt_enable <= instruction[0];
            // The bank has no interrupt input: a pre-empted REGBANK or RETURNI still switches
            // it (RETURNI to the saved bank, without popping); the entry pushed the old one.
            if (op_regbank) bank <= instruction[0];
            if (op_returni) bank <= stack_top[14];
        end
    end

    // Second cycle: register, flag and scratch-pad writes. INPUT takes in_port live; STORE
    // addresses the scratch pad through the sY port.
    always @(posedge clk) begin
        if (register_write_q)
            registers[{xb, sx_addr}] <= op_input ? in_port : result_q;
        if (scratch_pad_write_q)
            scratch_pad[spm_addr] <= sx;
        if (internal_reset)
            {carry, zero} <= 2'b00;
        else if (flag_write_q)
            {carry, zero} <= {carry_q, zero_q};
    end

`ifdef BOTSIM_DEBUG
    // ---- debug signals (botsim board --vcd builds only) ----------------------------------------
    // The names of Xilinx's KCPSM6 simulation model, for waveforms: the word on `instruction`
    // as text (botsim's disassembler, through the simulation host), the status (bank, Z, C,
    // interrupt enable, then Reset, Sleep or Intrp for an interrupt entry) and the active
    // bank's registers. The scratch pad is the `scratch_pad` array.
    import "DPI-C" function void botsim_disasm(input int word, output bit [159:0] text);
    /* verilator lint_off LITENDIAN */  // [1:160] and [1:128]: the names' ranges in Xilinx's model
    reg  [1:160] kcpsm6_opcode;
    initial botsim_disasm({14'd0, instruction}, kcpsm6_opcode);  // the power-up word's text too
    always @(instruction) botsim_disasm({14'd0, instruction}, kcpsm6_opcode);
    wire [1:128] kcpsm6_status = {bank ? "B" : "A", zero ? ", Z" : ",NZ", carry ? ", C" : ",NC",
                                  interrupt_enable ? ",IE" : ",ID",
                                  internal_reset || !run ? ",Reset" : t_state == T_IDLE ? ",Sleep" :
                                  active_interrupt ? ",Intrp" : "      "};
    wire [7:0] sim_s0 = registers[{bank, 4'h0}], sim_s1 = registers[{bank, 4'h1}];
    wire [7:0] sim_s2 = registers[{bank, 4'h2}], sim_s3 = registers[{bank, 4'h3}];
    wire [7:0] sim_s4 = registers[{bank, 4'h4}], sim_s5 = registers[{bank, 4'h5}];
    wire [7:0] sim_s6 = registers[{bank, 4'h6}], sim_s7 = registers[{bank, 4'h7}];
    wire [7:0] sim_s8 = registers[{bank, 4'h8}], sim_s9 = registers[{bank, 4'h9}];
    wire [7:0] sim_sA = registers[{bank, 4'hA}], sim_sB = registers[{bank, 4'hB}];
    wire [7:0] sim_sC = registers[{bank, 4'hC}], sim_sD = registers[{bank, 4'hD}];
    wire [7:0] sim_sE = registers[{bank, 4'hE}], sim_sF = registers[{bank, 4'hF}];
    /* verilator lint_on LITENDIAN */
`endif

endmodule
