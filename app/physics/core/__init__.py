"""What every model and example shares: parameters, closed-form models, reports, worked solutions."""
