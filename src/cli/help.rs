//! Examples shown under each command's `--help`.

pub const RUN: &str = "Examples:
  pipearm run                                      the default scenario, scenarios/default.toml
  pipearm run scenarios/string_strike.toml --csv   also the series as CSV and Parquet tables
  pipearm run my.toml --model 'modal(4)' --step 0.001 --integrator generalized-alpha
  pipearm run my.toml --no-record                  print the summary, write nothing";

pub const CHECK: &str = "Examples:
  pipearm check                                    every scenarios/*.toml against tests/baselines/
  pipearm check /abs/proj/scenarios/default.toml   the baselines of the scenario's own project
  pipearm check --bless                            accept the changes on purpose
  pipearm check --project /abs/proj --json";

pub const SEED: &str = "Examples:
  pipearm seed                                     every family under scenarios/seed/
  pipearm seed 3.4-contact --project /abs/proj --out /tmp/seed";

pub const BENCH: &str = "Examples:
  pipearm bench --quick                            the default scenario, a smaller grid
  pipearm bench scenarios/default.toml scenarios/lab.toml --out docs/accuracy";

pub const INIT: &str = "Examples:
  pipearm init my_arm && cd my_arm && pipearm run && pipearm check --bless";

pub const MODES: &str = "Examples:
  pipearm modes                                    the default arm with its payload
  pipearm modes scenarios/lab.toml --count 6";

pub const SWEEP: &str = "Examples:
  pipearm sweep scenarios/default.toml --vary payload.size=2-3/8,2-7/8,4-1/2
  pipearm sweep scenarios/default.toml --vary 'dampeners[0].gap_m=0..0.0004:0.0001' --shard 0/4
  pipearm sweep merge recordings/sweep";

pub const ENVELOPE: &str = "Examples:
  pipearm envelope scenarios/default.toml --spread 'dampeners[0].gap_m=uniform:0.0001..0.0003' --samples 64
  pipearm envelope merge recordings/envelope";

pub const DRAW: &str = "Examples:
  pipearm draw                                     the default scenario: recordings/default.machine.svg and .png
  pipearm draw scenarios/string_strike.toml        the lift with its well-centre guide
  pipearm draw robots/pipe_arm.urdf --out recordings/pipe_arm.svg   the robot alone";
