"""Page 1's parts beside the margins: the model's validity, the assumptions that decide the
verdict, the design limits, the flight record and the load margin along the orbit."""
