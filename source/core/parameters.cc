#include <coulomb_adapt/core/parameter_error.h>
#include <coulomb_adapt/core/parameters.h>

namespace coulomb_adapt
{
  namespace parameters
  {
    void
    Output::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Output");
      {
        prm.declare_entry("Output directory",
                          "output",
                          Patterns::DirectoryName(),
                          "Directory for all results of a run (created if "
                          "missing): VTU/PVTU/PVD or HDF5/XDMF files, "
                          "summary.json, the contact CSV files and "
                          "the resolved parameters.prm.");
        prm.declare_entry("Format",
                          "vtu",
                          Patterns::Selection(option_pattern<OutputFormat>()),
                          "File format of the per-cycle fields. vtu: .vtu "
                          "pieces per rank and cycle ('Cells per VTU "
                          "piece'), a .pvtu per cycle and a "
                          ".pvd per body indexing the cycles. hdf5: one .h5 "
                          "per body and cycle, written by all ranks "
                          "together (parallel HDF5), and a .xdmf per body "
                          "indexing the cycles (ParaView: open the .xdmf "
                          "with the 'Xdmf Reader'): one file per cycle "
                          "whatever the number of ranks, for parallel runs. "
                          "Its data are uncompressed doubles holding "
                          "32-bit floats' values (deal.II's patches), as "
                          "VTU's: on one rank "
                          "the files are about 4 times larger than the "
                          "compressed VTU and slower to write. With Open "
                          "MPI the files go through ROMIO: the program sets "
                          "OMPI_MCA_io=^ompio unless that variable is set "
                          "(OMPIO's semaphores, left locked by a killed run, "
                          "hung later runs; README).");
        prm.declare_entry("Write cycles",
                          "all",
                          Patterns::Selection(option_pattern<WriteCycles>()),
                          "Which cycles' fields are written: all, only the "
                          "last one (the mesh adaptation's result), or none. "
                          "summary.json and the contact CSV are written "
                          "after every cycle in any case. A run that stops "
                          "with an error writes no fields with 'last' (the "
                          "finished cycles' meshes were adapted away): "
                          "'all' keeps them.");
        prm.declare_entry(
          "Cells per VTU piece",
          "10000",
          Patterns::Integer(0, 1000000000),
          "With Format = vtu: each rank writes its cells' fields in .vtu "
          "pieces of at most this many cells (of nearly equal sizes; the "
          ".pvtu lists them all, rank by rank), on concurrent tasks: "
          "deal.II's VTU writer encodes and compresses a file on one "
          "thread. 0: one piece per rank. The pieces depend on the cells "
          "alone, not on the threads. Why: on blocks with epsilon_0 = "
          "0.25 % (169,302 DoFs, 1 rank, 2 threads) the output took "
          "0.60-0.67 s instead of 0.85-0.93 s with one piece per rank "
          "(benchmarks/adaptive_run).");
        prm.declare_entry(
          "Write in background",
          "true",
          Patterns::Bool(),
          "With Format = vtu: a cycle's .vtu pieces are encoded, compressed "
          "and written on a thread of their own while the next cycle "
          "remeshes and solves (which leaves one of two cores idle much of "
          "the time); the cycle's .pvtu, and its entry in the .pvd, follow "
          "when the next cycle writes its fields (or the run ends, also "
          "with an error). The last cycle is written at once, on all "
          "threads. Same files either way; the cycle's fields stay in memory "
          "until then (+25 MiB peak on the run below). Why: encoding and "
          "compressing are most of the output's time, and the run uses "
          "1.3 of 2 cores (blocks, epsilon_0 = 0.25 %, 1 rank: output "
          "0.72-0.88 s instead of 0.82-0.96 s, 6.1-8.3 % of the run "
          "instead of 7.7-8.2 %, four alternated pairs; the last cycle's "
          "0.4-0.5 s stays, benchmarks/adaptive_run). false: every cycle "
          "is written before the run goes on.");
        prm.declare_entry(
          "Write smoothed stress",
          "false",
          Patterns::Bool(),
          "true: the bodies' fields also hold the recovered stress of the zz "
          "or spr estimator (smoothed_stress_xx, _yy, _xy: the sigma* that "
          "the FE stress is compared with), for studying the estimator. "
          "false: not written, and the log says so. Why: three more nodal "
          "fields on a second DoFHandler were a quarter of the output's "
          "time (blocks, epsilon_0 = 0.25 %: 0.54-0.56 s instead of "
          "0.67-0.74 s with every cycle written in the foreground, 3 pairs; "
          "benchmarks/adaptive_run).");
        prm.declare_entry("Write VTU",
                          "true",
                          Patterns::Bool(),
                          "Kept for old parameter files: false is the same "
                          "as 'Write cycles = none' (and overrides it).");
      }
      prm.leave_subsection();
    }



    void
    Output::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Output");
      {
        directory    = prm.get("Output directory");
        format       = parse_option<OutputFormat>(prm.get("Format"));
        write_cycles = parse_option<WriteCycles>(prm.get("Write cycles"));
        cells_per_vtu_piece   = prm.get_integer("Cells per VTU piece");
        write_in_background   = prm.get_bool("Write in background");
        write_smoothed_stress = prm.get_bool("Write smoothed stress");
        if (!prm.get_bool("Write VTU"))
          write_cycles = WriteCycles::none;
      }
      prm.leave_subsection();
    }



    void
    Mesh::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Mesh");
      {
        prm.declare_entry("Cell type",
                          "quadrilateral",
                          Patterns::Selection(option_pattern<CellType>()),
                          "Reference cell of the built-in scenes' meshes: "
                          "structured quadrilaterals, or the same mesh with "
                          "every quadrilateral split into triangles (hertz: "
                          "a gmsh triangle mesh). For the gmsh scene a .geo "
                          "file is meshed with this cell type; a .msh file "
                          "keeps its own cells.");
        prm.declare_entry("Global refinements",
                          "0",
                          Patterns::Integer(0, 12),
                          "Number of uniform refinements of the scene's "
                          "coarse meshes before the first cycle.");
      }
      prm.leave_subsection();
    }



    void
    Mesh::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Mesh");
      {
        cell_type          = parse_option<CellType>(prm.get("Cell type"));
        global_refinements = prm.get_integer("Global refinements");
      }
      prm.leave_subsection();
    }



    void
    FiniteElements::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Finite elements");
      {
        prm.declare_entry("Polynomial degree",
                          "1",
                          Patterns::Integer(1, 2),
                          "Degree p of the displacement elements: Q_p on "
                          "quadrilaterals, P_p on triangles.");
        prm.declare_entry("Plane model",
                          "plane strain",
                          Patterns::Selection(option_pattern<PlaneModel>()),
                          "2D reduction of the elastic bodies. In plane "
                          "strain sigma_zz = nu (sigma_xx + sigma_yy) enters "
                          "the von Mises stress.");
      }
      prm.leave_subsection();
    }



    void
    FiniteElements::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Finite elements");
      {
        degree      = prm.get_integer("Polynomial degree");
        plane_model = parse_option<PlaneModel>(prm.get("Plane model"));
      }
      prm.leave_subsection();
    }



    namespace
    {
      // The cre estimator's entries of "Error indicator".
      void
      declare_cre_entries(ParameterHandler &prm)
      {
        prm.declare_entry("CRE degree increase",
                          "3",
                          Patterns::Integer(1, 4),
                          "k: the optimisation of the cre estimator's "
                          "tractions solves its local problems with "
                          "polynomials of degree p + k (the estimate itself: "
                          "p + k + 'CRE evaluation degree increase'). Their "
                          "discretisation error lowers the estimate: on the "
                          "manufactured solution epsilon(cre) changes by "
                          "up to 2 % from k = 3 to 4 (tests/cre_estimator; "
                          "4 % when the estimate was evaluated with degree "
                          "p + k, doc/indicator.md). With k >= 3 "
                          "the traction optimisation also uses edge "
                          "bubbles of degree p + 1.");
        prm.declare_entry("CRE traction optimisation",
                          "true",
                          Patterns::Bool(),
                          "true: the free parameters of the element "
                          "equilibration (one per interior or Dirichlet node "
                          "and component) minimise the estimate itself (one "
                          "sparse SPD solve; the bound stays guaranteed and "
                          "is tighter, above all on triangles). false: the "
                          "classical choice of Ladeveze and Leguillon, the "
                          "tractions closest to the averaged FE traction.");
        prm.declare_entry(
          "CRE evaluation degree increase",
          "1",
          Patterns::Integer(0, 2),
          "The cre estimate is evaluated with local problems of degree "
          "p + k + this; the optimisation of the edge tractions uses "
          "degree p + k ('CRE degree increase'). Its minimum is where "
          "those local problems see least of sigma^: evaluated with them, "
          "the estimate is low by more than their discretisation error "
          "(frictionless Q1 blocks, upper 4 x 4 and lower 6 x 7 cells: "
          "7.03 % against an exact 7.41 %; evaluated with one degree more "
          "7.34 %, two 7.42 %; doc/indicator.md 4b). Per body the classical "
          "tractions are kept where, evaluated the same way, they are "
          "lower. Costs one more local problem per cell, solved once. 0: "
          "the minimisation's estimate, as before 2026-11-30.");
        prm.declare_entry(
          "CRE relaxed equilibration",
          "true",
          Patterns::Bool(),
          "true (with traction optimisation and CRE degree "
          "increase >= 3): the optimisation also moves the "
          "edge tractions that keep every element in "
          "equilibrium but break the prolongation "
          "conditions (per interior edge a linear "
          "tangential traction, per interior node a "
          "linear normal traction on its edges whose "
          "couples cancel in each element; with degree 2 "
          "also the quadratic tangential and normal "
          "tractions of each edge with unknown tractions, "
          "on a roller the normal one only): sigma^ stays "
          "statically admissible and the estimate is much "
          "tighter (P1 triangles: effectivity about 1.02-1.2 "
          "instead of 1.6-2.1; evaluated with the "
          "minimisation's own local problems it fell 5 % below the "
          "error on a coarse Q1 mesh, doc/indicator.md 4b). Only "
          "used where the scene's "
          "displacement data are interpolated exactly (the "
          "bound assumes it), or with 'CRE lift of displacement "
          "data'; the log says when it is not. "
          "false: the prolongation conditions are kept.");
        prm.declare_entry(
          "CRE lift of displacement data",
          "true",
          Patterns::Bool(),
          "Only for displacement data that the FE space does not "
          "interpolate exactly (the manufactured scene's sinusoid). true: "
          "the relaxed equilibration is used there too, the local problems "
          "measure sigma^ - sigma(u^) with u^ = u_c + r, r a lift of the "
          "data's interpolation error (u^ meets the data), and the bound "
          "adds ||sigma(r)||: a bound up to quadrature and the local "
          "problems' discretisation, where the kept conditions are only "
          "measured above the error (manufactured, effectivity: P1 "
          "1.07-1.19 instead of 1.58-1.81, P2 1.04-1.12 instead of "
          "1.69-2.03, Q1 1.13-1.27 instead of 1.19-1.22, Q2 1.12-1.26 "
          "instead of 1.06-1.11; doc/indicator.md 4b). false: the "
          "prolongation conditions are kept there and no lift is added "
          "(the estimates measured above the error, but not a proof). "
          "Data that the FE space interpolates exactly (every contact "
          "scene) need no lift: nothing changes there.");
        prm.declare_entry(
          "CRE minimisation tolerance",
          "1e-3",
          Patterns::Double(0, 0.1),
          "With the relaxed equilibration: how exactly the free "
          "parameters minimise the estimate. > 0: by CG with an "
          "additive Schwarz preconditioner (per vertex its parameters and "
          "those of its edges), stopped when its last 10 steps together "
          "lowered a body's e^2 by less than this fraction of it: any "
          "iterate keeps sigma^ statically admissible, so the bound "
          "holds, and the estimate lies a little above the exact minimum "
          "(1e-3: by 0.01-0.3 % of epsilon on benchmarks/effectivity's "
          "meshes; on blocks the estimator takes "
          "1.7x less time than with the exact minimum at 6,836 DoFs, 2.2x "
          "less at 26,724, with 20 % less memory, as the factorisation's "
          "share grows with the mesh; doc/indicator.md). 0: the exact "
          "minimum, by a sparse direct factorisation (MUMPS LDL^T), up to "
          "'CRE exact minimisation up to' parameters per body. Either "
          "choice can change an adaptive run's meshes.");
        prm.declare_entry(
          "CRE exact minimisation up to",
          "200000",
          Patterns::Integer(0),
          "With 'CRE minimisation tolerance' = 0: the most free parameters "
          "a body's relaxed system may have for the exact minimum; a larger "
          "one is minimised by the truncated CG at tolerance 1e-3 instead "
          "(the log says so). Why: the factorisation's memory and time grow "
          "faster than the mesh (blocks at 420,228 DoFs, 2.5e6 parameters "
          "in all: 7.9 GB peak and 129 s for the estimator, against "
          "5.0 GB and 33 s truncated, epsilon 0.1 % higher; the bound "
          "holds either way). 0: no limit.");
      }
    } // namespace



    void
    ErrorIndicator::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Error indicator");
      {
        prm.declare_entry(
          "Estimator",
          "zz",
          Patterns::Selection(option_pattern<ErrorEstimator>()),
          "The a posteriori error estimator; the one that "
          "drives the adaptation. zz: the seed's, the "
          "corrected FE stress smoothed by global L2 "
          "projection onto the continuous FE space of the "
          "same degree (Zienkiewicz-Zhu 1987); spr: smoothed "
          "by superconvergent patch recovery (Zienkiewicz-Zhu "
          "1992); cre: error in constitutive relation with a "
          "statically admissible stress built by the element "
          "equilibration technique (Ladeveze-Leguillon 1983, "
          "Coorevits-Hild-Hjiaj 2001), an upper bound of the "
          "exact error for frictionless contact up to its "
          "local problems' discretisation (where the mortar's "
          "solution penetrates between its nodes the kinematic "
          "side is opened first, doc/indicator.md 4c); conforming meshes only (not with Adaptation/Strategy = "
          "refine). All three add the same contact term and "
          "use the seed's normalisation. With polynomial "
          "degree 2, zz underestimates, more so on finer "
          "meshes (manufactured, 4 uniform refinements: "
          "effectivity 0.45 to 0.09 with Q2, 0.69 to 0.54 "
          "with P2; spr 2.3 to 1.0 and 1.09 to 0.99, cre "
          "1.26 to 1.12 and 1.12 to 1.04): use spr or cre "
          "there.");
        prm.declare_entry("Recovery",
                          "",
                          Patterns::Anything(),
                          "Removed: replaced by 'Estimator' (zz | spr | cre). "
                          "A file that sets it is refused with a message "
                          "naming the new entry.");
        prm.declare_entry("Compare estimators",
                          "false",
                          Patterns::Bool(),
                          "Compute zz, spr and cre on the same solution in "
                          "every cycle (summary.json 'estimators', with "
                          "their effectivity when the exact error is "
                          "computed); 'Estimator' still drives the "
                          "adaptation. For studies of the estimators: it "
                          "costs the two other estimators' time.");
        declare_cre_entries(prm);
        prm.declare_entry("Compute exact error",
                          "false",
                          Patterns::Bool(),
                          "Also compute the exact error (3-8) and the "
                          "effectivity index epsilon / epsilon_exact: with "
                          "the scene's exact solution if it has one "
                          "(manufactured), otherwise with a reference "
                          "solution of the same scene on a finer mesh "
                          "(an extra, expensive solve: for verification).");
        prm.declare_entry("Reference refinements",
                          "2",
                          Patterns::Integer(1, 6),
                          "Uniform refinements of the reference mesh beyond "
                          "the mesh of the cycle (each multiplies the DoFs "
                          "by about 4).");
      }
      prm.leave_subsection();
    }



    void
    ErrorIndicator::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Error indicator");
      {
        const std::string removed = prm.get("Recovery");
        if (!removed.empty())
          throw ParameterError(
            "Error indicator/Recovery",
            removed,
            "this entry was replaced by 'Error indicator/Estimator' "
            "(zz | spr | cre): write 'set Estimator = " +
              (removed == "zz" || removed == "spr" ? removed :
                                                     std::string("zz")) +
              "' instead");
        estimator          = parse_option<ErrorEstimator>(prm.get("Estimator"));
        compare_estimators = prm.get_bool("Compare estimators");
        cre_degree_increase = prm.get_integer("CRE degree increase");
        cre_evaluation_degree_increase =
          prm.get_integer("CRE evaluation degree increase");
        cre_traction_optimisation = prm.get_bool("CRE traction optimisation");
        cre_relaxed_equilibration = prm.get_bool("CRE relaxed equilibration");
        cre_lift_displacement_data =
          prm.get_bool("CRE lift of displacement data");
        cre_minimisation_tolerance =
          prm.get_double("CRE minimisation tolerance");
        cre_exact_minimisation_up_to =
          prm.get_integer("CRE exact minimisation up to");
        compute_exact_error   = prm.get_bool("Compute exact error");
        reference_refinements = prm.get_integer("Reference refinements");
      }
      prm.leave_subsection();
    }



    namespace
    {
      // The cycles: how the mesh changes, how many cycles, and when they
      // stop (the target and its safety margin, the DoF limit).
      void
      declare_cycle_entries(ParameterHandler &prm)
      {
        prm.declare_entry("Strategy",
                          "uniform",
                          Patterns::Selection(
                            option_pattern<AdaptationStrategy>()),
                          "How the mesh changes from one cycle to the next. "
                          "uniform: every cell is refined once. refine: "
                          "quadrilaterals are refined and coarsened with "
                          "hanging nodes (p4est), cells chosen by the "
                          "'Refinement criterion'. remesh: each body is "
                          "remeshed by gmsh with triangles of the optimal "
                          "size field h*_E = r_E h_E (theory.md section 4).");
        prm.declare_entry("Number of cycles",
                          "1",
                          Patterns::Integer(1, 40),
                          "Maximum number of solve cycles; the mesh is "
                          "adapted between two cycles.");
        prm.declare_entry("Minimum number of cycles",
                          "1",
                          Patterns::Integer(1, 40),
                          "The cycles do not stop at the target before this "
                          "many: 2 is the seed's procedure (solve, build the "
                          "optimal mesh for epsilon_0, solve again) even when "
                          "the first mesh is already accurate enough.");
        prm.declare_entry("Target error",
                          "0",
                          Patterns::Double(0, 100),
                          "The prescribed accuracy epsilon_0, in percent: "
                          "the cycles stop once epsilon <= epsilon_0. 0: no "
                          "target, run 'Number of cycles' cycles (required "
                          "> 0 by 'remesh' and by 'Refinement criterion = "
                          "size ratio', which aim at it).");
        prm.declare_entry("Over-refinement ratio",
                          "0",
                          Patterns::Double(0, 1),
                          "With 'remesh' and a target: a mesh whose epsilon "
                          "is below this fraction of epsilon_0 counts as "
                          "over-refined, and is optimised again (coarser) "
                          "instead of stopping, as long as two cycles are "
                          "left. An overestimating estimator (cre) plans too "
                          "fine from a coarse mesh; 0.8 brings it close to "
                          "the optimal mesh at the cost of cycles. 0: stop "
                          "at any epsilon <= epsilon_0.");
        prm.declare_entry("Target safety factor",
                          "0.95",
                          Patterns::Double(0.5, 1),
                          "'remesh' and 'refine' with 'size ratio' plan "
                          "the optimal mesh for this fraction of epsilon_0, "
                          "divided by the ratio of the epsilon measured on "
                          "the last planned mesh to its plan's prediction: "
                          "the error model of theory.md section 4 is "
                          "asymptotic, and a plan for exactly epsilon_0 "
                          "lands a few % above it about as often as below, "
                          "which costs a whole further cycle. 1: plan for "
                          "epsilon_0 itself (the seed's procedure), still "
                          "corrected by the measured ratio.");
        prm.declare_entry("Maximum number of DoFs",
                          "2e6",
                          Patterns::Double(1),
                          "No further cycle once a cycle has at least this "
                          "many DoFs (both bodies). The size-ratio "
                          "adaptation ('remesh', 'refine' with 'size ratio') "
                          "also plans no mesh above it: if the optimal mesh "
                          "for the target has more cells than this many DoFs "
                          "allow (at the current DoFs per cell), the optimal "
                          "mesh of that size is built instead (the log and "
                          "summary.json's 'limited_by_max_dofs' say so). "
                          "'refine' rounds to whole levels and may land up "
                          "to 4 times above it.");
        prm.declare_entry("Minimum number of cells",
                          "100",
                          Patterns::Double(0),
                          "The size-ratio adaptation ('remesh', 'refine' "
                          "with 'size ratio') plans no mesh with fewer cells "
                          "(both bodies): if the optimal mesh for the target "
                          "has fewer, the optimal mesh of this many is built "
                          "instead, and an over-refined mesh built so is not "
                          "coarsened again. On coarser meshes the estimate "
                          "loses its meaning: blocks, epsilon_0 = 15 %, "
                          "coarsened to 4 + 4 triangles, where zz gave 4.9 % "
                          "against an exact error of 21 % "
                          "(doc/adaptation.md). 0: no minimum.");
      }



      // Which cells change and by how much: the refinement criterion and
      // the bounds of the size ratio r_E.
      void
      declare_size_entries(ParameterHandler &prm)
      {
        prm.declare_entry("Refinement criterion",
                          "size ratio",
                          Patterns::Selection(
                            option_pattern<RefinementCriterion>()),
                          "For 'Strategy = refine': which cells are refined "
                          "and coarsened. size ratio: from r_E of theory.md "
                          "section 4 (r_E < 1/2 refine, r_E > 2 coarsen). "
                          "fixed fraction / fixed number: deal.II's "
                          "GridRefinement with 'Refine fraction' and "
                          "'Coarsen fraction' (of the error, or of the "
                          "cells). optimize: the number of refined cells "
                          "that minimises the predicted error times the "
                          "cell count (GridRefinement's 'optimize').");
        prm.declare_entry("Refine fraction",
                          "0.3",
                          Patterns::Double(0, 1),
                          "fixed fraction / fixed number: fraction of the "
                          "squared error (or of the cells) refined.");
        prm.declare_entry("Coarsen fraction",
                          "0.03",
                          Patterns::Double(0, 1),
                          "fixed fraction / fixed number: fraction of the "
                          "squared error (or of the cells) coarsened.");
        prm.declare_entry("Minimum size ratio",
                          "0.1",
                          Patterns::Double(0.001, 1),
                          "Lower bound of r_E = h*_E / h_E: how much finer "
                          "one cycle may make a cell (near a singular point "
                          "this to the power 3/2). Once a plan has been "
                          "checked against the mesh it built, a plan that "
                          "the bound keeps from its aim is made again with "
                          "the bounds to the power 3/2.");
        prm.declare_entry("Maximum size ratio",
                          "4",
                          Patterns::Double(1, 100),
                          "Upper bound of r_E: how much coarser one cycle "
                          "may make a cell.");
        prm.declare_entry("Singular convergence rate",
                          "0.5",
                          Patterns::Double(0.01, 10),
                          "Local convergence rate q used in r_E for cells "
                          "near a singular point (ends of the contact zone, "
                          "points where a clamped or contact boundary "
                          "meets another boundary condition; near: the point "
                          "in the cell or closer to it than half the cell's "
                          "diameter): min(p, this). Elsewhere q = p, the "
                          "polynomial degree.");
      }
    } // namespace



    void
    Adaptation::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Adaptation");
      {
        declare_cycle_entries(prm);
        declare_size_entries(prm);
        prm.declare_entry("Remeshing algorithm",
                          "frontal-delaunay",
                          Patterns::Selection(
                            option_pattern<RemeshingAlgorithm>()),
                          "gmsh's 2D algorithm for 'Strategy = remesh': "
                          "frontal-delaunay (gmsh's default, better shaped "
                          "triangles) or delaunay (about half the meshing "
                          "time, slightly more cells for the same size "
                          "field).");
        prm.declare_entry("Remeshing split above cells",
                          "5000",
                          Patterns::Integer(0),
                          "For 'Strategy = remesh': a body whose size field "
                          "asks for more cells than this is meshed by gmsh "
                          "with 2^k times the sizes (about 4^k times fewer "
                          "triangles, gmsh's time is per triangle) and each "
                          "triangle is then split into 4 at its edges' "
                          "midpoints, k times (red refinement: the angles "
                          "stay gmsh's, midpoints on curved boundaries go "
                          "onto the curve); k is the smallest with at most "
                          "this many cells for gmsh. 0: never split.");
        prm.declare_entry("Warm start",
                          "true",
                          Patterns::Bool(),
                          "Start the semismooth Newton method of a cycle "
                          "from the contact sets (open/stick/slip) of the "
                          "previous cycle, transferred to the new slave "
                          "nodes, instead of from the initial gap (a load "
                          "path: its first load step from the previous "
                          "cycle's sets after that step).");
        prm.declare_entry(
          "Nested start above DoF ratio",
          "16",
          Patterns::Double(0),
          "A cycle whose meshes have at least this many times the previous "
          "cycle's DoFs (both bodies) starts its contact solve from nested "
          "iteration instead of the warm start: coarser meshes (remeshed "
          "triangles: the scene's meshes refined uniformly, up to the "
          "finest with at most the cycle's DoFs; quadrilaterals refined in "
          "place: the cycle's own meshes with their finest cell levels "
          "coarsened) solved as 'Contact/Nested iteration levels' says, and "
          "the Newton iteration starts from the finest one's sets. Why: "
          "after a large "
          "refinement the previous cycle's few contact nodes place the "
          "stick/slip front only roughly, and the Newton iteration moves it "
          "about one node per step and side (blocks, refine, "
          "epsilon_0 = 0.5 %: 18 steps from 144 to 27,470 DoFs). Static "
          "scenes only (a load path keeps its warm start), and only above "
          "'Contact/Nested iteration minimum DoFs'; 0: always the warm "
          "start.");
      }
      prm.leave_subsection();
    }



    void
    Adaptation::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Adaptation");
      {
        const std::string path = "Adaptation/";
        strategy   = parse_option<AdaptationStrategy>(prm.get("Strategy"));
        n_cycles   = prm.get_integer("Number of cycles");
        min_cycles = prm.get_integer("Minimum number of cycles");
        over_refinement_ratio = prm.get_double("Over-refinement ratio");
        require_parameter(min_cycles <= n_cycles,
                          path + "Minimum number of cycles",
                          min_cycles,
                          "at most 'Number of cycles' (" +
                            std::to_string(n_cycles) + ")");
        target_error         = prm.get_double("Target error") / 100;
        target_safety_factor = prm.get_double("Target safety factor");
        max_dofs             = prm.get_double("Maximum number of DoFs");
        min_cells            = prm.get_double("Minimum number of cells");
        // A plan aims at the safety factor times epsilon_0 and lands near
        // it: with the ratio at or above it, every mesh would count as
        // over-refined and be optimised again until the cycles run out.
        // (Only 'remesh' uses the rule.)
        require_parameter(strategy != AdaptationStrategy::remesh ||
                            over_refinement_ratio < target_safety_factor,
                          path + "Over-refinement ratio",
                          over_refinement_ratio,
                          "below 'Target safety factor' (" +
                            format_value(target_safety_factor) +
                            "), the fraction of epsilon_0 the plans aim at; "
                            "0 switches the rule off");
        refinement_criterion =
          parse_option<RefinementCriterion>(prm.get("Refinement criterion"));
        refine_fraction        = prm.get_double("Refine fraction");
        coarsen_fraction       = prm.get_double("Coarsen fraction");
        min_size_ratio         = prm.get_double("Minimum size ratio");
        max_size_ratio         = prm.get_double("Maximum size ratio");
        singular_rate          = prm.get_double("Singular convergence rate");
        warm_start             = prm.get_bool("Warm start");
        nested_start_dof_ratio = prm.get_double("Nested start above DoF ratio");
        require_parameter(nested_start_dof_ratio == 0 ||
                            nested_start_dof_ratio >= 2,
                          path + "Nested start above DoF ratio",
                          nested_start_dof_ratio,
                          "0 (never) or at least 2: a cycle with less than "
                          "twice the previous cycle's DoFs is no large "
                          "refinement, and its warm start is good (one "
                          "uniform refinement has about 4 times the DoFs)");
        remeshing_algorithm =
          parse_option<RemeshingAlgorithm>(prm.get("Remeshing algorithm"));
        remeshing_split_above_cells =
          prm.get_integer("Remeshing split above cells");
        require_parameter(refine_fraction + coarsen_fraction <= 1,
                          path + "Refine fraction",
                          refine_fraction,
                          "Refine fraction + Coarsen fraction <= 1");
        const bool aims_at_target =
          strategy == AdaptationStrategy::remesh ||
          (strategy == AdaptationStrategy::refine &&
           refinement_criterion == RefinementCriterion::size_ratio);
        require_parameter(!aims_at_target || target_error > 0,
                          path + "Target error",
                          100 * target_error,
                          "a value > 0 (percent) with Strategy = remesh or "
                          "Refinement criterion = size ratio, which build "
                          "the mesh for that accuracy");
      }
      prm.leave_subsection();
    }



  } // namespace parameters



  void
  Parameters::declare_parameters(ParameterHandler &prm)
  {
    parameters::Mesh::declare_parameters(prm);
    parameters::FiniteElements::declare_parameters(prm);
    parameters::Contact::declare_parameters(prm);
    parameters::LinearSolver::declare_parameters(prm);
    parameters::ErrorIndicator::declare_parameters(prm);
    parameters::Adaptation::declare_parameters(prm);
    parameters::Output::declare_parameters(prm);
  }



  void
  Parameters::parse_parameters(ParameterHandler &prm)
  {
    mesh.parse_parameters(prm);
    finite_elements.parse_parameters(prm);
    contact.parse_parameters(prm);
    linear_solver.parse_parameters(prm);
    error_indicator.parse_parameters(prm);
    adaptation.parse_parameters(prm);
    output.parse_parameters(prm);
    // deal.II 9.4 refines simplices only globally, and gmsh remeshes with
    // triangles: each strategy needs its cell type.
    if (adaptation.strategy == AdaptationStrategy::refine &&
        mesh.cell_type != CellType::quadrilateral)
      throw ParameterError("Adaptation/Strategy",
                           "refine",
                           "'refine' needs 'Mesh/Cell type = "
                           "quadrilateral' (hanging nodes); for triangles "
                           "use 'remesh' or 'uniform'");
    if (adaptation.strategy == AdaptationStrategy::refine &&
        (error_indicator.estimator == ErrorEstimator::cre ||
         error_indicator.compare_estimators))
      throw ParameterError(
        error_indicator.compare_estimators ?
          "Error indicator/Compare estimators" :
          "Error indicator/Estimator",
        error_indicator.compare_estimators ? "true" : "cre",
        "the cre estimator's element equilibration is written for "
        "conforming meshes, and 'Adaptation/Strategy = refine' makes "
        "hanging nodes: use 'Strategy = remesh' (triangles) or 'uniform'");
    if (adaptation.strategy == AdaptationStrategy::remesh &&
        mesh.cell_type != CellType::triangle)
      throw ParameterError("Adaptation/Strategy",
                           "remesh",
                           "'remesh' needs 'Mesh/Cell type = triangle' "
                           "(gmsh remeshes with triangles); for "
                           "quadrilaterals use 'refine' or 'uniform'");
  }
} // namespace coulomb_adapt
