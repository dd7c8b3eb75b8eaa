// A testbench in the project's simulation file set: botsim must not read it (it would be a
// second top, and it is not even valid Verilog).
module tb;
  this is not Verilog
endmodule
