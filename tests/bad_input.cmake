# Bad input, faults and the first run (issue 13): each test runs glide on a
# faulty scene, command line or environment through check_error.py and
# checks the exit status (1 input error, 2 load step failed, 4 input/output
# error, 143 SIGTERM), the message (it names the parameter or file and what
# to do), that nothing crashed or hung (60 s per run), and what is on disk:
# nothing after an input error; the user's files untouched; after a fault,
# complete files only and indexes (.pvd files, statistics.csv) that agree.
# Tests that cannot run here (permissions as root, mounting a small tmpfs)
# exit with 77, which ctest reports as skipped, never as passed.
set(BLOCK ${SCENES}/block.prm)
set(PARAMETERS ${CMAKE_SOURCE_DIR}/parameters)
set(CHECK ${GLIDE_PYTHON} ${SCENES}/check_error.py --glide $<TARGET_FILE:glide> --timeout 60)

function(glide_bad_input name)
  add_test(NAME error.${name} COMMAND ${CHECK} ${ARGN})
  set_tests_properties(error.${name} PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 300
    ENVIRONMENT "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1;OMPI_MCA_rmaps_base_oversubscribe=1")
endfunction()

# 3D variant of the test block. (%3B stands for ";", which CMake cannot pass
# inside an argument; check_error.py turns it back.)
set(BLOCK_3D --set "Dimension=3" --set "Analysis type=3d" --set "Body block/Block/Lower corner=0, 0, 0"
  --set "Body block/Block/Upper corner=2, 1, 1" --set "Body block/Block/Subdivisions=4, 2, 2"
  --set "Boundary condition load/Function=t%3B -5*t%3B 0")

# Values that make the solve meaningless: every function value is checked
# for finiteness where it is evaluated (CheckedFunction), moduli and
# Poisson's ratio within what double precision resolves, every body held.
glide_bad_input(value.nan_traction --expect "Boundary condition load/Function' = 'sqrt\\(x-1\\)%3B -5\\*t': component 1 evaluates to NaN at \\(0"
  -- ${BLOCK} --set "Boundary condition load/Function=sqrt(x-1)%3B -5*t")
glide_bad_input(value.inf_traction --expect "Boundary condition load/Function.*evaluates to \\+infinity.*division by zero"
  -- ${BLOCK} --set "Boundary condition load/Function=t/0%3B -5*t")
glide_bad_input(value.inf_at_last_load_factor --expect "Boundary condition load/Function.*component 2 evaluates to -infinity.*t = 1"
  -- ${BLOCK} --set "Boundary condition load/Function=0%3B -5/(1-t)")
glide_bad_input(value.nan_displacement --expect "Boundary condition bottom/Function.*NaN"
  -- ${BLOCK} --set "Boundary condition bottom/Type=displacement" --set "Boundary condition bottom/Function=0%3B log(-1-t)")
glide_bad_input(value.nan_body_force --expect "Body block/Body force.*NaN"
  -- ${BLOCK} --set "Body block/Body force=0%3B (x-x)/(y-y)")
glide_bad_input(value.inf_pressure --expect "Boundary condition load/Function.*\\+infinity"
  -- ${BLOCK} --set "Boundary condition load/Type=pressure" --set "Boundary condition load/Function=1e300*1e300*t")
glide_bad_input(value.nan_in_3d --expect "Boundary condition load/Function.*component 3 evaluates to NaN"
  -- ${BLOCK} ${BLOCK_3D} --set "Boundary condition load/Function=t%3B -5*t%3B sqrt(z-2)")
glide_bad_input(value.nan_rigid_motion --expect "Body punch/Rigid body/Translation.*NaN"
  -- ${PARAMETERS}/rigid-punch-meshed.prm --set "Body punch/Rigid body/Translation=0%3B sqrt(-1-t)")
glide_bad_input(value.inf_modulus --expect "Young's modulus=inf'.*does not match"
  -- ${BLOCK} --set "Body block/Material/Young's modulus=inf")
glide_bad_input(value.nan_modulus --expect "Young's modulus=nan'.*does not match"
  -- ${BLOCK} --set "Body block/Material/Young's modulus=nan")
glide_bad_input(value.huge_modulus --expect "Body block/Material/Young's modulus' = 1e\\+308 is outside 1e-100 <= E <= 1e100"
  -- ${BLOCK} --set "Body block/Material/Young's modulus=1e308")
glide_bad_input(value.tiny_modulus --expect "Young's modulus' = 1e-300 is outside"
  -- ${BLOCK} --set "Body block/Material/Young's modulus=1e-300")
glide_bad_input(value.zero_modulus --expect "Body block/Material/Young's modulus' must be greater than zero"
  -- ${BLOCK} --set "Body block/Material/Young's modulus=0")
glide_bad_input(value.negative_modulus --expect "Young's modulus=-5'.*does not match"
  -- ${BLOCK} --set "Body block/Material/Young's modulus=-5")
glide_bad_input(value.nearly_incompressible --expect "Body block/Material/Poisson's ratio' = 0.4999999999 must satisfy -0.9999 <= nu <= 0.4999.*0.49"
  -- ${BLOCK} --set "Body block/Material/Poisson's ratio=0.4999999999")
glide_bad_input(value.poisson_near_minus_one --expect "Poisson's ratio' = -0.99999 must satisfy"
  -- ${BLOCK} --set "Body block/Material/Poisson's ratio=-0.99999")
glide_bad_input(value.moduli_ratio --expect "Young's moduli of 'Body lower' \\(1e\\+06\\) and 'Body upper' \\(1e-07\\) differ by more than a factor of 1e\\+12.*rigid"
  -- ${PARAMETERS}/patch-test.prm --set "Body upper/Material/Young's modulus=1e-7")
glide_bad_input(value.huge_penalty --expect "Contact pair punch/Penalty stiffness' = 1e\\+300 is more than 1e\\+12 times"
  -- ${PARAMETERS}/rigid-punch.prm --set "Contact pair punch/Enforcement=penalty" --set "Contact pair punch/Penalty stiffness=1e300")
glide_bad_input(value.empty_scene --expect "nothing that loads or moves its bodies.*Boundary condition"
  -- ${SCENES}/errors/empty-scene.prm)
glide_bad_input(value.all_fixed_no_load --expect "nothing that loads or moves its bodies"
  -- ${BLOCK} --set "Boundary condition load/Type=fixed")
glide_bad_input(value.traction_only --expect "Body 'block' is not held: nothing stops its translation in x, translation in y and rotation about z around \\(1, 0.5\\).*Type = fixed"
  -- ${BLOCK} --set "Boundary condition bottom/Type=traction" --set "Boundary condition bottom/Function=0%3B 10*t")
glide_bad_input(value.free_translation --expect "Body 'block' is not held: nothing stops its translation in x \\("
  -- ${BLOCK} --set "Boundary condition bottom/Type=YSYMM")
glide_bad_input(value.free_rotation_about_a_point --expect "Body 'block' is not held: nothing stops its rotation about z around \\(0, 0\\)"
  -- ${BLOCK} --set "Node sets=corner" --set "Node set corner/Points=0, 0" --set "Boundary condition bottom/Surface=corner")
glide_bad_input(value.free_in_3d --expect "Body 'block' is not held: nothing stops its translation in x, translation in y and rotation about the axis along \\(0, 0, 1\\) through \\(1, 0.5, 0"
  -- ${BLOCK} ${BLOCK_3D} --set "Boundary condition bottom/Type=ZSYMM" --set "Boundary condition bottom/Surface=block.back")
glide_bad_input(value.free_axisymmetric --expect "Body 'block' is not held: nothing stops its translation along the axis \\(y\\)"
  -- ${BLOCK} --set "Analysis type=axisymmetric" --set "Boundary condition bottom/Type=XSYMM")
glide_bad_input(value.held_only_by_open_contact --status 2 --expect "load step 1 failed.*Note: body 'block' is held against its translation in x, translation in y and rotation about z around \\(1, 0.5\\) only by contact"
  -- ${BLOCK} --set "Boundary condition bottom/Type=traction" --set "Boundary condition bottom/Function=0%3B 1*t"
     --set "Contact pairs=floor" --set "Contact pair floor/Slave=block.bottom" --set "Contact pair floor/Master=rigid plane"
     --set "Contact pair floor/Rigid master/Point=0, -1" --set "Load stepping/Maximum cut-backs=1")
# The load step failed: the output directory exists (it is not an input
# error), so only the status and the message are checked here.

# Sizes: estimated before the mesh is built.
glide_bad_input(size.subdivisions_2d --expect "about 1e\\+10 cells.*GiB.*Lower 'Body block/Block/Subdivisions'"
  -- ${BLOCK} --set "Body block/Block/Subdivisions=100000, 100000")
glide_bad_input(size.refinements_2d --expect "too large.*Body block/Refinement/Global refinements.*by 4"
  -- ${BLOCK} --set "Body block/Refinement/Global refinements=12" --set "Discretization/Element degree=2")
glide_bad_input(size.refinements_3d --expect "too large.*Global refinements.*by 8"
  -- ${BLOCK} ${BLOCK_3D} --set "Body block/Refinement/Global refinements=12")
glide_bad_input(size.subdivisions_3d --expect "too large.*about 1.25e\\+11 cells"
  -- ${BLOCK} ${BLOCK_3D} --set "Body block/Block/Subdivisions=5000, 5000, 5000")
glide_bad_input(size.round_shape_3d --expect "too large.*Body sphere/Refinement/Global refinements"
  -- ${PARAMETERS}/hertz-3d.prm --set "Body sphere/Refinement/Global refinements=12")

# Command line.
glide_bad_input(cli.set_without_equals --expect "--set 'abc' is not of the form.*has no '='" -- ${BLOCK} --set "abc")
glide_bad_input(cli.set_empty_path --expect "--set '=3': the path '' has an empty part" -- ${BLOCK} --set "=3")
glide_bad_input(cli.set_empty_part --expect "--set 'Body block//Mesh=block'.*empty part" -- ${BLOCK} --set "Body block//Mesh=block")
glide_bad_input(cli.set_trailing_slash --expect "--set 'Body block/=3'.*empty part" -- ${BLOCK} --set "Body block/=3")
glide_bad_input(cli.set_unknown_section --expect "--set 'Nowhere/Entry=1': the scene has no subsection 'Nowhere'\\. Run 'glide --print-parameters'" -- ${BLOCK} --set "Nowhere/Entry=1")
# A misspelt body or entry on the command line: the name it was meant to be
# (deal.II's "You can't ask for entry ... you have not yet declared" before).
glide_bad_input(cli.set_misspelt_body --expect "--set 'Body blok/Material/Young's modulus=2': the scene has no subsection 'Body blok'\\. Did you mean 'Body block'\\?" -- ${BLOCK} --set "Body blok/Material/Young's modulus=2")
glide_bad_input(cli.set_body_not_in_bodies --expect "--set 'Body punch/Material/Young's modulus=2': the scene has no subsection 'Body punch'\\. The scene's subsections 'Body \\.\\.\\.' are 'Body block' \\(one for each name in 'Bodies'%3B add a name there for a new one\\)" -- ${BLOCK} --set "Body punch/Material/Young's modulus=2")
glide_bad_input(cli.set_misspelt_entry --expect "--set 'Body block/Material/Youngs modulus=2': there is no entry 'Youngs modulus' in subsection 'Body block/Material'\\. Did you mean 'Young's modulus'\\?" -- ${BLOCK} --set "Body block/Material/Youngs modulus=2")
glide_bad_input(cli.set_missing_argument --expect "--set needs an argument" -- ${BLOCK} --set)
glide_bad_input(cli.print_parameters_format --expect "--print-parameters takes prm, json or xml, not 'yaml'" -- --print-parameters yaml)
glide_bad_input(cli.print_parameters_full_stdout --stdout full --status 4 --expect "input/output error: Cannot write the parameters to standard output" -- --print-parameters)
glide_bad_input(cli.print_parameters_closed_stdout --stdout closed --status 4 --expect "input/output error: Cannot write the parameters to standard output" -- --print-parameters json)
glide_bad_input(cli.version_full_stdout --stdout full --status 4 --expect "Cannot write the version to standard output" -- --version)
glide_bad_input(cli.help_full_stdout --stdout full --status 4 --expect "Cannot write the help to standard output" -- --help)

# Scene names are plain names inside the output directory.
glide_bad_input(name.dot --expect "'Scene name' = '.' starts with '.'" -- ${BLOCK} --set "Scene name=.")
glide_bad_input(name.dotdot --expect "'Scene name' = '..' starts with '.'" -- ${BLOCK} --set "Scene name=..")
glide_bad_input(name.parent --expect "'Scene name' = '../escape' contains a path separator" -- ${BLOCK} --set "Scene name=../escape")
glide_bad_input(name.slash --expect "'Scene name' = 'a/b' contains a path separator" -- ${BLOCK} --set "Scene name=a/b")
glide_bad_input(name.backslash --expect "'Scene name' = 'a.b' contains a path separator" -- ${BLOCK} "--set" "Scene name=a\\b")
glide_bad_input(name.hidden --expect "'Scene name' = '.hidden' starts with '.'" -- ${BLOCK} --set "Scene name=.hidden")
glide_bad_input(name.empty_from_file_name --copy-scene-as .prm --expect "the scene name is empty.*Set 'Scene name'" -- ${BLOCK} --set "Scene name=")
glide_bad_input(name.hidden_file_name --copy-scene-as .block.prm --expect "the scene name '.block' \\(the scene file's name without extension\\) starts with '.'.*set 'Scene name'" -- ${BLOCK})
glide_bad_input(name.empty_output_directory --expect "'Output/Directory' is empty%3B use '.'" -- ${BLOCK} --set "Output/Directory=")

# The output directory: never a file of the user's deleted or overwritten;
# a directory that cannot be made is an input/output error (4), on every
# process.
glide_bad_input(output.directory_is_a_file --setup file --status 4 --expect "Cannot create the output directory.*Not a directory.*Output/Directory" -- ${BLOCK})
glide_bad_input(output.directory_under_a_file --setup under-file --status 4 --expect "Cannot create the output directory.*afile/sub/block" -- ${BLOCK})
glide_bad_input(output.foreign_files --setup foreign --status 4 --expect "already holds files that glide did not write \\(e.g. 'notes.txt'" -- ${BLOCK})
glide_bad_input(output.foreign_file_with_a_glide_name --setup foreign-glide-name --status 4 --expect "already holds files that glide did not write \\(e.g. 'statistics.csv'" -- ${BLOCK})
glide_bad_input(output.unwritable --setup unwritable --status 4 --expect "Cannot create the output directory.*Permission denied" -- ${BLOCK})
glide_bad_input(output.rerun_keeps_user_files --setup rerun-with-user-file --status 0 -- ${BLOCK})
glide_bad_input(output.mpi_directory_under_a_file --setup under-file --status 4 --mpirun "${GLIDE_MPIRUN} -np 2 --oversubscribe"
  --expect "Cannot create the output directory" -- ${BLOCK})
# Open MPI's parallel file writing aborted (a buffer overflow, after the
# solve) on result file names of about 256 characters or more.
string(REPEAT "a" 220 LONG_NAME)
glide_bad_input(output.mpi_file_names_too_long --status 4 --mpirun "${GLIDE_MPIRUN} -np 2 --oversubscribe"
  --expect "Under MPI the results' file names may be at most 240 characters.*Choose a shorter 'Output/Directory' or 'Scene name'"
  -- ${BLOCK} --set "Scene name=${LONG_NAME}")

# Faults during a run: killed, or the disk full.
set(LONG_BLOCK ${BLOCK} --set "Load stepping/Number of steps=400" --set "Body block/Block/Subdivisions=40, 20"
  --set "Discretization/Geometric nonlinearity=true")
set(LONG_PUNCH ${PARAMETERS}/rigid-punch.prm --set "Load stepping/Number of steps=200")
glide_bad_input(fault.sigterm --fault sigterm --status 143 --expect "stopped by signal SIGTERM" -- ${LONG_BLOCK})
glide_bad_input(fault.sigterm_contact --fault sigterm --status 143 --expect "stopped by signal SIGTERM" -- ${LONG_PUNCH})
# The signals a batch system sends before it ends a job (SLURM's --signal,
# PBS: SIGUSR1), a CPU time limit (SIGXCPU) and a terminal's quit key
# (SIGQUIT) stop the run as SIGTERM does: until 2026-12-06 their default
# action ended glide in the middle of a file.
glide_bad_input(fault.sigusr1 --fault sigusr1 --status 138 --expect "stopped by signal SIGUSR1" -- ${LONG_BLOCK})
glide_bad_input(fault.sigxcpu_contact --fault sigxcpu --status 152 --expect "stopped by signal SIGXCPU" -- ${LONG_PUNCH})
glide_bad_input(fault.sigquit --fault sigquit --status 131 --expect "stopped by signal SIGQUIT" -- ${LONG_BLOCK})
glide_bad_input(fault.sigkill --fault sigkill -- ${LONG_BLOCK})
glide_bad_input(fault.sigkill_contact --fault sigkill -- ${LONG_PUNCH})
glide_bad_input(fault.disk_full --fault disk-full --disk-size 160k --status 4 --expect "input/output error: .*disk.* full" -- ${LONG_BLOCK})
# A result file that reaches the process's file size limit (ulimit -f)
# is an input/output error that says so; until 2026-12-06 SIGXFSZ ended
# glide in the middle of the file.
# (MPI's start-up needs files of a few MiB, so the limit is 8 MiB and the
# block's VTU about 20 MiB.)
glide_bad_input(fault.file_size_limit --fault file-size-limit --file-size-limit 8192 --status 4
  --expect "input/output error: .*File too large%3B the file size limit of the process \\(ulimit -f\\) was reached"
  -- ${BLOCK} --set "Body block/Block/Subdivisions=480, 240" --set "Load stepping/Number of steps=1")
glide_bad_input(fault.disk_full_contact --fault disk-full --disk-size 1m --status 4 --expect "input/output error: .*(disk.* full|cut short)" -- ${LONG_PUNCH})
