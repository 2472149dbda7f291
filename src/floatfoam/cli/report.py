"""``floatfoam report``: theory of every case and every finished CFD run, as HTML + Markdown."""

from __future__ import annotations


def add_arguments(parser) -> None:
    """The report command's arguments (shared with postprocess/report.py)."""
    parser.add_argument("--out", metavar="DIR",
                        help="output folder (default: <build>/report; with --cases, "
                             "<build>/report-<its name>-<8 hex digits>)")
    parser.add_argument("--cases", metavar="DIR", help="cases folder (default: the project's)")
    parser.add_argument("--build", metavar="DIR",
                        help="folder of the runs, <build>/<case>/<level>/motion.csv "
                             "(default: the project's build/)")
    parser.add_argument("--no-potential", dest="potential", action="store_false",
                        help="leave potential flow out: its row, Cummins' model (the Δ columns "
                             "then against the linear theory) and the A(ω), B(ω) figure")
    parser.add_argument("--no-pictures", dest="pictures", action="store_false",
                        help="leave the pictures of the flow out (pyvista; 10-20 s per run "
                             "the first time, reused after)")


def register(sub) -> None:
    p = sub.add_parser("report", help="write build/report/index.html and index.md")
    add_arguments(p)
    p.set_defaults(func=run)


def run(args) -> int:
    from floatfoam.analysis.report import Sources, build_report

    html = build_report(cases_dir=args.cases, build_dir=args.build, out_dir=args.out,
                        sources=Sources.default(include_potential=args.potential),
                        pictures=args.pictures)
    print(f"report: {html} (and {html.with_suffix('.md')})")
    return 0
