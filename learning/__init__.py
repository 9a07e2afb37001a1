"""Training environments, PPO training, evaluation and studies.

Never imported by a playing agent."""
