"""The playing agent: transport, agent loop, strategy, team launcher and the command line."""
