from etcheck.cli.main import run

run()
