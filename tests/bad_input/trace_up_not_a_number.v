/* the up direction must be three numbers */
trace up: 0,up,0
