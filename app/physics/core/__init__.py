"""What every model and example shares: the model contract, parameters, closed-form models, reports, worked
solutions."""
