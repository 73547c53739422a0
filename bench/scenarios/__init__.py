"""One module per scenario of bench/README.md, each with `run(bench)`."""
