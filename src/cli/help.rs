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
  pipearm sweep scenarios/casing_arm.toml --vary payload.size=casing,drill-collar --out recordings/casing-arm
  pipearm sweep scenarios/default.toml --vary 'dampeners[0].gap_m=0..0.0004:0.0001' --out recordings/gaps --shard 0/2
  pipearm sweep scenarios/default.toml --vary 'dampeners[0].gap_m=0..0.0004:0.0001' --out recordings/gaps --shard 1/2
  pipearm sweep merge recordings/gaps                  when every shard is done";

pub const ENVELOPE: &str = "Examples:
  pipearm envelope scenarios/default.toml --spread 'dampeners[0].gap_m=uniform:0.0001..0.0003' --samples 64
  pipearm envelope merge recordings/envelope";

pub const DESIGN: &str = "Examples:
  pipearm design scenarios/default.toml --minimize drive.duration_s --over drive.duration_s=8..25 \\
      --limit 'residual.amplitude_m<=0.001' --limit 'peak_force_n<=3000' \\
      --spread 'dampeners[0].gap_m=uniform:0..0.0004' --samples 8 --budget 12
  pipearm design scenarios/default.toml --table --limit 'residual.amplitude_m<=0.001' --nominal";

pub const COMPARE: &str = "Examples:
  pipearm compare scenarios/default.toml --measured measurements/rig.csv --shift
  pipearm compare scenarios/default.toml --measured measurements/rig.csv --model 'modal(2)' --out /tmp/cmp";

pub const FIT: &str = "Examples:
  pipearm fit scenarios/default.toml --measured measurements/rig.csv --params 'dampeners[0].law.stiffness' --shift
  pipearm fit scenarios/default.toml --measured measurements/rig.csv \\
      --params 'dampeners[0].law.stiffness,arm.damping_ratios[0]' --step 0.001 --shift";

pub const PIPES: &str = "Examples:
  pipearm pipes                                    the whole catalogue
  pipearm pipes 9-5/8                              every 9-5/8 in row
  pipearm pipes drill-pipe 5                       5 in drill pipe
  pipearm pipes 9-5/8@47.00                        one row, by its entry";

pub const CAPACITY: &str = "Examples:
  pipearm capacity                                 the default scenario's machine and string
  pipearm capacity scenarios/servo.toml --step-deg 15";
pub const DRAW: &str = "Examples:
  pipearm draw                                     the default scenario: recordings/default.machine.svg and .png
  pipearm draw scenarios/string_strike.toml        the lift with its well-centre guide
  pipearm draw robots/pipe_arm.urdf --out recordings/pipe_arm.svg   the robot alone";
